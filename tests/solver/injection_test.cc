// No text of the user's reaches a shell or a gnuplot command. A campaign
// whose level labels, channel names and step file names hold shell and
// gnuplot syntax (quotes, $(...), backticks, '.system(...).', markup), and
// output paths that hold the same, go through every command that plots or
// takes a screenshot (diagnose --curves, report with --screenshot, the
// measured backbone and its report): each succeeds, draws its plot, shows
// the texts as written, and the sentinel file that any of those commands
// would create never appears. A label with a control character is refused
// at read time (exit 2) naming campaign.json and the field. The program is
// run with an argument vector (solver/report/external_program.h), so the
// test itself gives no shell a chance either.
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "solver/report/external_program.h"
#include "solver/report/gnuplot_script.h"
#include "solver/report/html_screenshot.h"
#include "tests/support/file_bytes.h"
#include "tests/support/paper_scenario.h"
#include "tests/support/png_image.h"
#include "tests/support/temp_path.h"

namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using ::testing::Not;

using beamid::testing::ProgramRun;
using beamid::testing::ReadFile;
using beamid::testing::WriteFile;

void ReplaceAll(std::string& text, const std::string& from, const std::string& to) {
  for (std::size_t at = 0; (at = text.find(from, at)) != std::string::npos; at += to.size())
    text.replace(at, from.size(), to);
}

bool IsPng(const fs::path& path) {
  std::error_code error;
  return fs::is_regular_file(path, error) && fs::file_size(path, error) > 1000 &&
         ReadFile(path).compare(0, 8, "\x89PNG\r\n\x1a\n") == 0;
}

// The <svg>...</svg> pieces of a page: the plots, apart from its tables.
std::string Plots(const std::string& html) {
  std::string plots;
  for (std::size_t at = html.find("<svg"); at != std::string::npos; at = html.find("<svg", at + 1))
    plots += html.substr(at, html.find("</svg>", at) - at);
  return plots;
}

class Injection : public ::testing::Test {
 protected:
  // Runs beamid with these arguments, in the suite's folder.
  static ProgramRun Beamid(const std::vector<std::string>& arguments) {
    const fs::path out = root_ / "run.out", err = root_ / "run.err";
    const int status = beamid::solver::RunExternalProgram({.program = BEAMID_EXECUTABLE,
                                                           .arguments = arguments,
                                                           .debian_package = "(the beamid build)",
                                                           .stdout_file = out,
                                                           .stderr_file = err});
    return {status, ReadFile(out) + ReadFile(err)};
  }

  static void SetUpTestSuite() {
    root_ = beamid::testing::UniqueTempPath("beamid_injection");
    fs::remove_all(root_);
    fs::create_directories(root_);
    // A relative `touch SENTINEL` of an injected shell lands here too.
    previous_folder_ = fs::current_path();
    fs::current_path(root_);
    sentinel_ = root_ / "SENTINEL";
    const std::string touch = "touch " + sentinel_.string();
    low_ = "low'; " + touch + "; echo '";
    high_ = "high\"$(" + touch + ")`" + touch + "`'.system('" + touch + "').' acc_2^{x}@&~\\ 50%s";
    channels_ = {"acc1'.system('" + touch + "').'", "acc2$(" + touch + ")", "acc3`" + touch + "`"};
    out_ = root_ / "out '\"$(touch SENTINEL)`touch SENTINEL`#?% x";
    fs::create_directories(out_);

    WriteFile(root_ / "scenario.json",
              beamid::testing::PaperScenarioJson("injection", R"([
      {"label": "low", "force_amplitude_N": 0.5, "frequencies_Hz": {"start": 53.6, "stop": 54.6, "step": 0.5}},
      {"label": "high", "force_amplitude_N": 1.0, "frequencies_Hz": {"start": 53.6, "stop": 54.6, "step": 0.5}}])",
                                                 5));
    setup_ = Beamid({"-q", "simulate", (root_ / "scenario.json").string(), "-o", (root_ / "clean").string()});
    if (setup_.exit_code != 0) return;
    MakeHostileCampaign();
    result_ = out_ / "result'$(touch SENTINEL).json";
    setup_ = Beamid({"-q", "identify", campaign_.string(), "--fit", channels_[0] + "," + channels_[1], "--validate",
                     channels_[2], "-o", result_.string()});
    if (setup_.exit_code == 5) setup_.exit_code = 0;  // fitted, but missing the data: still a result to plot
  }

  // The clean campaign copied with hostile level labels, channel names (in
  // campaign.json and every recording's header) and step file names.
  static void MakeHostileCampaign() {
    campaign_ = root_ / "campaign '$(touch SENTINEL)";
    fs::copy(root_ / "clean", campaign_, fs::copy_options::recursive);
    nlohmann::json json = nlohmann::json::parse(ReadFile(campaign_ / "campaign.json"));
    for (std::size_t c = 0; c < 3; ++c) json["sensors"][c]["channel"] = channels_[c];
    int i = 0;
    for (auto& step : json["steps"]) {
      step["level"] = step["level"] == "low" ? low_ : high_;
      const fs::path old_file = campaign_ / step["file"].get<std::string>();
      std::string header_and_rest = ReadFile(old_file);
      const std::size_t end = header_and_rest.find('\n');
      std::string header = header_and_rest.substr(0, end);
      for (std::size_t c = 0; c < 3; ++c) ReplaceAll(header, "acc" + std::to_string(c + 1), channels_[c]);
      const std::string name = "step'$(touch SENTINEL)`touch SENTINEL`\"#?% " + std::to_string(i++) + ".csv";
      WriteFile(campaign_ / name, header + header_and_rest.substr(end));
      fs::remove(old_file);
      step["file"] = name;
    }
    WriteFile(campaign_ / "campaign.json", json.dump(2));
  }

  static void TearDownTestSuite() {
    fs::current_path(previous_folder_);
    fs::remove_all(root_);
  }

  void SetUp() override { ASSERT_EQ(setup_.exit_code, 0) << setup_.output; }
  void TearDown() override { ExpectNoSentinel(); }

  static void ExpectNoSentinel() {
    for (const auto& entry : fs::recursive_directory_iterator(root_))
      EXPECT_NE(entry.path().filename(), "SENTINEL") << entry.path();
  }

  static inline fs::path root_, previous_folder_, sentinel_, out_, campaign_, result_;
  static inline std::string low_, high_;
  static inline std::vector<std::string> channels_;
  static inline ProgramRun setup_;
};

TEST_F(Injection, DiagnoseDrawsItsCurvesWithTheLabelsAsText) {
  const fs::path curves = out_ / "curves'$(touch SENTINEL)`touch SENTINEL`";
  const ProgramRun run =
      Beamid({"diagnose", campaign_.string(), "--fit", channels_[0] + "," + channels_[1], "--validate", channels_[2],
              "--candidates", "support_friction", "--no-recording-check", "-o",
              (out_ / "diagnosis'$(touch SENTINEL).json").string(), "--curves", curves.string()});
  ASSERT_EQ(run.exit_code, 0) << run.output;
  EXPECT_THAT(run.output, Not(HasSubstr("not drawn")));
  EXPECT_TRUE(IsPng(curves.string() + ".png"));
  // The script holds the labels and names only as quoted texts, and reads
  // no file and runs no command.
  const std::string script = ReadFile(curves.string() + ".gp");
  for (const std::string& text : {low_, high_})
    EXPECT_THAT(script, HasSubstr("title " + beamid::solver::GnuplotText(text))) << text;
  for (const std::string& channel : channels_) {
    std::string title = beamid::solver::GnuplotText(channel + " (points:");
    title.pop_back();  // the title goes on: no closing quote here
    EXPECT_THAT(script, HasSubstr("set title " + title)) << channel;
  }
  EXPECT_THAT(script, Not(HasSubstr("\"<")));
  EXPECT_THAT(script, Not(HasSubstr("awk")));
  EXPECT_THAT(script, Not(HasSubstr("set output")));
}

TEST_F(Injection, TheReportAndItsScreenshotShowTheNamesAsWritten) {
  const fs::path html = out_ / "report'$(touch SENTINEL)#?%.html";
  const fs::path png = out_ / "shot'$(touch SENTINEL)`touch SENTINEL`#?% .png";
  const bool chromium = beamid::solver::FindChromium().has_value();
  std::vector<std::string> arguments = {"report", result_.string(), "-o", html.string()};
  if (chromium) arguments.insert(arguments.end(), {"--screenshot", png.string()});
  const ProgramRun run = Beamid(arguments);
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const std::string plots = Plots(ReadFile(html));
  EXPECT_GE(std::count(plots.begin(), plots.end(), '\n'), 100);
  // gnuplot drew the names in its SVG text as written (no markup, no cut):
  // here the parts that no XML escaping changes.
  EXPECT_THAT(plots, HasSubstr("acc2$(touch " + sentinel_.string() + ")"));
  EXPECT_THAT(plots, HasSubstr(".system("));
  EXPECT_THAT(plots, HasSubstr("acc_2^{x}@"));
  EXPECT_THAT(plots, HasSubstr("~\\ 50%s"));
  if (!chromium) GTEST_SKIP() << "no Chromium: the screenshot is not checked (scripts/install-deps.sh installs it)";
  ASSERT_TRUE(IsPng(png)) << run.output;
  // The page itself, not Chromium's "file not found": plots cover a good
  // part of it.
  const beamid::testing::PngImage image = beamid::testing::ReadPng(png.string());
  std::size_t drawn = 0;
  for (const auto& pixel : image.rgb) drawn += pixel[0] < 200 || pixel[1] < 200 || pixel[2] < 200;
  EXPECT_GT(static_cast<double>(drawn) / image.rgb.size(), 0.01);
}

TEST_F(Injection, TheMeasuredBackboneAndItsReportTakeTheHostileNames) {
  const fs::path prefix = out_ / "backbone'$(touch SENTINEL)";
  const ProgramRun backbone =
      Beamid({"-q", "backbone", "--measured", campaign_.string(), "--channel", channels_[2], "-o", prefix.string()});
  ASSERT_EQ(backbone.exit_code, 0) << backbone.output;
  const fs::path html = out_ / "backbone report'$(touch SENTINEL).html";
  const ProgramRun report = Beamid({"-q", "report", prefix.string() + ".json", "-o", html.string()});
  ASSERT_EQ(report.exit_code, 0) << report.output;
  EXPECT_THAT(Plots(ReadFile(html)), HasSubstr("<path"));
}

TEST_F(Injection, ALabelWithAControlCharacterIsRefusedNamingTheField) {
  const fs::path spoiled = root_ / "spoiled";
  fs::copy(root_ / "clean", spoiled, fs::copy_options::recursive);
  nlohmann::json json = nlohmann::json::parse(ReadFile(spoiled / "campaign.json"));
  json["steps"][1]["level"] = "low\nset output '/tmp/x'\nsystem 'touch " + sentinel_.string() + "'";
  WriteFile(spoiled / "campaign.json", json.dump(2));
  const ProgramRun run = Beamid({"diagnose", spoiled.string(), "--fit", "acc1,acc2", "-o",
                                 (root_ / "d.json").string(), "--curves", (root_ / "c").string()});
  EXPECT_EQ(run.exit_code, 2) << run.output;
  EXPECT_THAT(run.output, HasSubstr("campaign.json"));
  EXPECT_THAT(run.output, HasSubstr("\"steps[1].level\" holds the control character 0x0A"));
  EXPECT_FALSE(fs::exists(root_ / "c.png"));
}

}  // namespace
