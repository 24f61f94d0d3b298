// beamid batch, through the real program: four small campaigns from the
// independent time-domain simulator identified two at a time must give, per
// campaign, exactly the result `beamid identify` gives on it alone, and a
// summary (summary.csv, index.html) that holds those numbers and links each
// report; a campaign that fails is a row with the program's message and
// sets the exit code, without stopping the others; --collect rebuilds the
// same summary from the folders alone; outputs never land in a campaign.
#include <sys/wait.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "solver/estimation/result_io.h"
#include "solver/workflow/batch_entry.h"
#include "solver/workflow/batch_summary.h"
#include "tests/support/paper_scenario.h"
#include "tests/support/temp_path.h"

namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using ::testing::Not;

struct ProgramRun {
  int exit_code = -1;
  std::string output;
};

ProgramRun Beamid(const std::string& arguments) {
  const fs::path log = beamid::testing::UniqueTempPath("beamid_batch_test") += ".log";
  const std::string command = std::string(BEAMID_EXECUTABLE) + " " + arguments + " > " + log.string() + " 2>&1";
  const int status = std::system(command.c_str());
  std::stringstream text;
  text << std::ifstream(log).rdbuf();
  fs::remove(log);
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, text.str()};
}

std::string ReadFile(const fs::path& path) {
  std::stringstream text;
  text << std::ifstream(path).rdbuf();
  return text.str();
}

// A CSV line's cells, quotes honoured (the verdict holds commas).
std::vector<std::string> CsvCells(const std::string& line) {
  std::vector<std::string> cells(1);
  bool quoted = false;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (c == '"' && quoted && i + 1 < line.size() && line[i + 1] == '"') {
      cells.back() += '"';
      ++i;
    } else if (c == '"') {
      quoted = !quoted;
    } else if (c == ',' && !quoted) {
      cells.emplace_back();
    } else {
      cells.back() += c;
    }
  }
  return cells;
}

// The summary's rows by folder, each a map from header to cell.
std::map<std::string, std::map<std::string, std::string>> SummaryRows(const fs::path& csv) {
  std::istringstream in(ReadFile(csv));
  std::string line;
  std::getline(in, line);
  const std::vector<std::string> header = CsvCells(line);
  std::map<std::string, std::map<std::string, std::string>> rows;
  while (std::getline(in, line)) {
    const std::vector<std::string> cells = CsvCells(line);
    EXPECT_EQ(cells.size(), header.size()) << line;
    std::map<std::string, std::string> row;
    for (std::size_t i = 0; i < std::min(cells.size(), header.size()); ++i) row[header[i]] = cells[i];
    rows[row["folder"]] = row;
  }
  return rows;
}

class BatchCommand : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    folder_ = beamid::testing::UniqueTempPath("beamid_batch_test");
    fs::remove_all(folder_);
    fs::create_directories(folder_);
    // Two levels of five steps about the resonance: a fit with a held-out channel in about a second.
    const std::string levels =
        R"([{"label": "low", "force_amplitude_N": 1.0, "frequencies_Hz": {"start": 53, "stop": 55, "step": 0.5}},
            {"label": "high", "force_amplitude_N": 4.0, "frequencies_Hz": {"start": 53, "stop": 55, "step": 0.5}}])";
    for (int i = 0; i < 4; ++i) {
      const fs::path scenario = folder_ / ("scenario" + std::to_string(i) + ".json");
      std::ofstream(scenario) << beamid::testing::PaperScenarioJson("specimen " + std::to_string(i), levels, 50 + i);
      const ProgramRun run = Beamid("-q simulate " + scenario.string() + " -o " + Campaign(i).string());
      ASSERT_EQ(run.exit_code, 0) << run.output;
    }
  }
  static void TearDownTestSuite() { fs::remove_all(folder_); }
  static fs::path Campaign(int i) { return folder_ / ("specimen_" + std::to_string(i)); }
  static std::string Campaigns() {
    std::string list;
    for (int i = 0; i < 4; ++i) list += Campaign(i).string() + " ";
    return list;
  }
  static fs::path folder_;
};
fs::path BatchCommand::folder_;

TEST_F(BatchCommand, EachCampaignIsIdentifyOnItAloneAndTheSummaryHoldsItsNumbers) {
  const fs::path out = folder_ / "out";
  // The options before the campaigns, as a shell's glob puts them: a channel list takes one argument.
  const ProgramRun run = Beamid("batch --fit acc1,acc2 --validate acc3 " + Campaigns() + "-j 2 -o " + out.string());
  ASSERT_EQ(run.exit_code, 0) << run.output;
  EXPECT_THAT(run.output, HasSubstr("4 campaigns in"));
  const auto rows = SummaryRows(out / "summary.csv");
  ASSERT_EQ(rows.size(), 4u);
  const std::string index = ReadFile(out / "index.html");
  for (int i = 0; i < 4; ++i) {
    const std::string name = "specimen_" + std::to_string(i);
    const fs::path alone = folder_ / ("alone_" + name + ".json");
    const ProgramRun identify = Beamid("-q identify " + Campaign(i).string() +
                                       " --fit acc1,acc2 --validate acc3 --workers 1 -o " + alone.string());
    ASSERT_EQ(identify.exit_code, 0) << identify.output;
    const beamid::solver::ResultFile expected = beamid::solver::ReadResultFile(alone);
    const beamid::solver::ResultFile batched = beamid::solver::ReadResultFile(out / name / "result.json");
    ASSERT_EQ(batched.parameters.size(), expected.parameters.size());
    const auto& row = rows.at(name);
    EXPECT_EQ(row.at("status"), "fitted");
    EXPECT_EQ(row.at("campaign"), fs::weakly_canonical(Campaign(i)).string());
    EXPECT_EQ(row.at("campaign_name"), "specimen " + std::to_string(i));
    EXPECT_EQ(row.at("within_noise"), "1");
    EXPECT_NEAR(std::stod(row.at("reduced_chi_square")), expected.fit.reduced_chi_square,
                1e-5 * expected.fit.reduced_chi_square);
    for (std::size_t j = 0; j < expected.parameters.size(); ++j) {
      const auto& p = expected.parameters[j];
      // The process of its own gives the same fit to the last bit.
      EXPECT_EQ(batched.parameters[j].value, p.value) << name << " " << p.name;
      EXPECT_EQ(batched.parameters[j].std, p.std) << name << " " << p.name;
      const std::string unit = " [" + p.unit + "]";
      EXPECT_NEAR(std::stod(row.at(p.name + unit)), p.value, 1e-8 * std::abs(p.value) + 1e-300) << p.name;
      EXPECT_NEAR(std::stod(row.at(p.name + " lower_95" + unit)), p.lower_95, 1e-8 * std::abs(p.lower_95)) << p.name;
      EXPECT_NEAR(std::stod(row.at(p.name + " upper_95" + unit)), p.upper_95, 1e-8 * std::abs(p.upper_95)) << p.name;
    }
    EXPECT_EQ(row.at("report"), name + "/report.html");
    EXPECT_TRUE(fs::is_regular_file(out / name / "report.html"));
    EXPECT_THAT(index, HasSubstr("<a href=\"" + name + "/report.html\">specimen " + std::to_string(i) + "</a>"));
  }
  EXPECT_THAT(index, HasSubstr("4 campaigns: 4 fitted within their noise, 0 fitted beyond it"));
  EXPECT_THAT(index, Not(HasSubstr("class=\"flag\"")));

  // The summary from the folders alone, as after a cluster's job array.
  const std::string csv = ReadFile(out / "summary.csv");
  fs::remove(out / "summary.csv");
  fs::remove(out / "index.html");
  const ProgramRun collect = Beamid("-q batch --collect -o " + out.string());
  ASSERT_EQ(collect.exit_code, 0) << collect.output;
  EXPECT_EQ(ReadFile(out / "summary.csv"), csv);
  EXPECT_EQ(ReadFile(out / "index.html"), index);
}

TEST_F(BatchCommand, AFailedCampaignIsARowWithTheProgramsMessageAndTheOthersStand) {
  const fs::path out = folder_ / "failing";
  const fs::path missing = folder_ / "no_such_campaign";
  // A campaign named as the summary's own files gets a folder of its own.
  const fs::path named_as_index = folder_ / "index.html";
  const ProgramRun run = Beamid("batch " + Campaign(0).string() + " " + missing.string() + " " +
                                named_as_index.string() + " -o " + out.string());
  EXPECT_EQ(run.exit_code, 2) << run.output;
  EXPECT_THAT(run.output, HasSubstr("2 of 3 campaigns failed"));
  EXPECT_THAT(run.output, HasSubstr("the first, no_such_campaign: "));
  EXPECT_THAT(run.output, HasSubstr("no_such_campaign/campaign.json"));
  const auto rows = SummaryRows(out / "summary.csv");
  ASSERT_EQ(rows.size(), 3u);
  EXPECT_EQ(rows.at("index.html-2").at("status"), "failed");
  EXPECT_EQ(rows.at("specimen_0").at("status"), "fitted");
  EXPECT_EQ(rows.at("no_such_campaign").at("status"), "failed");
  EXPECT_EQ(rows.at("no_such_campaign").at("exit_code"), "2");
  EXPECT_THAT(rows.at("no_such_campaign").at("message"), HasSubstr("give the folder that holds campaign.json"));
  EXPECT_EQ(rows.at("no_such_campaign").at("k1 [N*m/rad]"), "");
  EXPECT_THAT(ReadFile(out / "index.html"), HasSubstr("<tr class=\"flag\">"));
}

TEST_F(BatchCommand, OutputsNeverLandInACampaignAndACampaignIsGivenOnce) {
  const std::string one = Campaign(0).string();
  ProgramRun run = Beamid("batch " + one + " -o " + (Campaign(0) / "results").string());
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_THAT(run.output, HasSubstr("lies inside"));
  run = Beamid("batch " + one + " -o " + Campaign(1).string());
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_THAT(run.output, HasSubstr("holds a campaign (campaign.json)"));
  run = Beamid("batch " + one + " " + one + "/ -o " + (folder_ / "twice").string());
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_THAT(run.output, HasSubstr("given twice"));
  run = Beamid("batch --collect " + one + " -o " + (folder_ / "twice").string());
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_THAT(run.output, HasSubstr("takes no campaign"));
  EXPECT_FALSE(fs::exists(Campaign(1) / "summary.csv"));
  EXPECT_FALSE(fs::exists(Campaign(0) / "results"));
}

// An entry that names a file outside its folder (written by hand or by
// someone else) is left out of the summary with a warning, never read.
TEST(BatchSummary, AnEntryNamingAFileOutsideItsFolderIsLeftOut) {
  const fs::path out = beamid::testing::UniqueTempPath("beamid_batch_summary");
  fs::remove_all(out);
  fs::create_directories(out / "a");
  fs::create_directories(out / "b");
  beamid::workflow::BatchEntry entry{.campaign = "/x/a", .status = beamid::workflow::BatchStatus::kFailed,
                                     .exit_code = 2, .message = "bad, \"quoted\" input"};
  beamid::workflow::WriteBatchEntry(out / "a" / "batch.json", entry);
  entry.campaign = "/x/b";
  entry.result_file = "../a/result.json";
  beamid::workflow::WriteBatchEntry(out / "b" / "batch.json", entry);
  const beamid::workflow::BatchSummary summary = beamid::workflow::CollectBatch(out);
  ASSERT_EQ(summary.rows.size(), 1u);
  EXPECT_EQ(summary.rows[0].folder, "a");
  ASSERT_EQ(summary.warnings.size(), 1u);
  EXPECT_THAT(summary.warnings[0], HasSubstr("result_file '../a/result.json' is not a file name"));
  // The message stays one cell.
  EXPECT_THAT(beamid::workflow::BatchSummaryCsv(summary), HasSubstr(",\"bad, \"\"quoted\"\" input\","));
  fs::remove_all(out);
}

}  // namespace
