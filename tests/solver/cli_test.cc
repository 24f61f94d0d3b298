// The beamid program itself: each command runs from a clean folder, writes
// what it says, and bad input ends with exit code 2 and a message naming
// the file and what to fix. Every command has --help with an example and the
// global --quiet and --progress; progress is text on a terminal and JSON on
// request; failure to converge ends with exit code 3.
#include <sys/wait.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>
#include <algorithm>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "solver/diagnosis/candidate_physics.h"
#include "solver/estimation/prediction_io.h"
#include "tests/support/csv_text.h"
#include "tests/support/paper_scenario.h"
#include "tests/support/temp_path.h"

namespace {

using ::testing::HasSubstr;

struct ProgramRun {
  int exit_code = -1;
  std::string output;  // stdout and stderr
};

// Runs `prefix beamid arguments`; stderr_only: stdout is dropped (for the
// JSON lines on stderr).
ProgramRun BeamidAfter(const std::string& prefix, const std::string& arguments, bool stderr_only = false) {
  const auto log = beamid::testing::UniqueTempPath("beamid_cli_test") += ".log";
  const std::string command = prefix + std::string(BEAMID_EXECUTABLE) + " " + arguments +
                              (stderr_only ? " 2> " + log.string() + " > /dev/null" : " > " + log.string() + " 2>&1");
  const int status = std::system(command.c_str());
  std::stringstream text;
  text << std::ifstream(log).rdbuf();
  std::filesystem::remove(log);
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, text.str()};
}

ProgramRun Beamid(const std::string& arguments, bool stderr_only = false) {
  return BeamidAfter("", arguments, stderr_only);
}

std::string ReadFile(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

class CommandLine : public ::testing::Test {
 protected:
  void SetUp() override {
    folder_ = beamid::testing::UniqueTempPath("beamid_cli_test");
    std::filesystem::remove_all(folder_);
    std::filesystem::create_directories(folder_);
  }
  void TearDown() override { std::filesystem::remove_all(folder_); }
  std::filesystem::path folder_;
};

TEST_F(CommandLine, FrcWritesCurvesWithStabilityForEachLevel) {
  const ProgramRun run = Beamid("-q frc examples/paper_setup/model.json --force-N 1,4 --from-hz 53 --to-hz 56 -o " +
                         (folder_ / "frc").string());
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const std::string csv = ReadFile(folder_ / "frc.csv");
  EXPECT_THAT(csv, HasSubstr("force_N,frequency_Hz,stable,theta_h1_amp_rad"));
  EXPECT_THAT(csv, HasSubstr("acc3_h3_acc_amp_m_s2"));
  EXPECT_GT(std::count(csv.begin(), csv.end(), '\n'), 50);
  EXPECT_THAT(ReadFile(folder_ / "frc.json"), HasSubstr("\"turning_points\""));
}

TEST_F(CommandLine, BackboneWritesFrequencyAgainstAmplitude) {
  const ProgramRun run = Beamid("backbone examples/paper_setup/model.json --points 20 -o " + (folder_ / "bb").string());
  ASSERT_EQ(run.exit_code, 0) << run.output;
  EXPECT_THAT(run.output, HasSubstr("backbone: 54.0"));
  EXPECT_THAT(ReadFile(folder_ / "bb.csv"), HasSubstr("theta_amp_rad,frequency_Hz,force_N,ms_frequency_Hz"));
}

TEST_F(CommandLine, BadInputEndsWithExitCodeTwoAndSaysWhatToFix) {
  ProgramRun run = Beamid("frc " + (folder_ / "missing.json").string());
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_THAT(run.output, HasSubstr("missing.json"));
  std::ofstream(folder_ / "typo.json") << R"({"beam": {"length_m": 0.6, "width_m": 0.04, "thickness_m": 0.005,
    "youngs_modulus_Pa": 2.1e11, "density_kg_m3": 7850}, "support": {"polynomial": {"k1_Nm_rad": 150, "k3": 4e5}},
    "excitation": {"position_m": 0.57}})";
  run = Beamid("backbone " + (folder_ / "typo.json").string());
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_THAT(run.output, HasSubstr("\"support.polynomial.k3\" is not a field here"));
  run = Beamid("identify " + (folder_ / "no_campaign").string() + " --fit acc1");
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_THAT(run.output, HasSubstr("no_campaign"));
  run = Beamid("frc examples/paper_setup/model.json --harmonics 0");
  EXPECT_EQ(run.exit_code, 2);
  run = Beamid("diagnose " + (folder_ / "no_campaign").string() + " --candidates gravity");
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_THAT(run.output, HasSubstr("gravity"));
  // The known ones are the library's, every one of them.
  for (const auto& name : beamid::solver::CandidateNames()) {
    if (name != "none") {
      EXPECT_THAT(run.output, HasSubstr(name));
    }
  }
}

// Option values out of range are refused before any file is read or any
// computation starts, naming the option (they used to end as exit 3 "did not
// converge", as exit 1, or not at all).
TEST_F(CommandLine, OptionsOutOfRangeAreBadInputNamedBeforeAnyWork) {
  const std::string campaign = (folder_ / "no_campaign").string();
  const struct {
    std::string arguments, named;
  } cases[] = {
      {"identify " + campaign + " --starts -1", "--starts"},
      {"identify " + campaign + " --workers -3", "--workers"},
      {"identify " + campaign + " -H 0", "--harmonics"},
      {"identify " + campaign + " -H 100000", "--harmonics"},
      {"identify " + campaign + " -H 2", "--fit-harmonics 3 exceeds the model's -H 2"},
      {"identify " + campaign + " --fit-harmonics 9", "--fit-harmonics 9 exceeds"},
      {"diagnose " + campaign + " --significance 5", "--significance"},
      {"diagnose " + campaign + " --workers -1", "--workers"},
      {"diagnose " + campaign + " -H 1", "--fit-harmonics 3 exceeds the model's -H 1"},
      {"identify " + campaign + " --phasor-uncertainty floor", "--phasor-uncertainty: floor not in"},
      {"diagnose " + campaign + " --phasor-uncertainty 1", "--phasor-uncertainty: 1 not in"},
      {"identify " + campaign + " -o /proc/beamid/result.json", "-o /proc/beamid/result.json: cannot write there"},
      {"identify " + campaign + " -o " + folder_.string(), "is a folder"},
      {"extract " + (folder_ / "data").string() + " -o " + (folder_ / "data" / "campaign.json").string(),
       "is also an input of this command"},
  };
  for (const auto& c : cases) {
    const ProgramRun run = Beamid(c.arguments);
    EXPECT_EQ(run.exit_code, 2) << c.arguments << "\n" << run.output;
    EXPECT_THAT(run.output, HasSubstr(c.named)) << c.arguments;
    EXPECT_THAT(run.output, ::testing::Not(HasSubstr("no_campaign"))) << "refused before reading: " << c.arguments;
  }
}

TEST_F(CommandLine, VersionIsPrinted) {
  const ProgramRun run = Beamid("--version");
  EXPECT_EQ(run.exit_code, 0) << run.output;
  EXPECT_THAT(run.output, ::testing::MatchesRegex("beamid [0-9]+\\.[0-9]+\\.[0-9]+\n"));
}

// Outputs are whole or absent: `simulate` killed at any moment leaves either
// a complete campaign or a folder without campaign.json (which no command
// reads as a campaign), also when it was replacing an earlier campaign.
TEST_F(CommandLine, AKilledSimulationNeverLeavesAHalfCampaignThatReads) {
  std::ofstream(folder_ / "scenario.json") << beamid::testing::PaperScenarioJson("cli test: kill", R"([
    {"label": "low", "force_amplitude_N": 0.5, "frequencies_Hz": {"start": 53.6, "stop": 54.6, "step": 0.25}}])", 5);
  const std::string campaign = (folder_ / "campaign").string();
  const std::string simulate = "-q simulate " + (folder_ / "scenario.json").string() + " --overwrite -o " + campaign;
  int complete = 0, absent = 0;
  for (const char* seconds : {"0.05", "0.3", "0.8", "1.5", "3", "60"}) {
    BeamidAfter(std::string("timeout -s KILL ") + seconds + " ", simulate);
    const ProgramRun extract = Beamid("-q extract " + campaign + " -o " + (folder_ / "phasors.json").string());
    if (std::filesystem::exists(folder_ / "campaign" / "campaign.json")) {
      EXPECT_EQ(extract.exit_code, 0) << "killed after " << seconds << " s:\n" << extract.output;
      ++complete;
    } else {
      EXPECT_EQ(extract.exit_code, 2) << "killed after " << seconds << " s:\n" << extract.output;
      EXPECT_THAT(extract.output, HasSubstr("campaign.json"));
      ++absent;
    }
  }
  // The last run was given time to finish; an early kill leaves no campaign.
  EXPECT_GE(complete, 1);
  EXPECT_GE(absent, 1);
}

TEST_F(CommandLine, IdentifyWithTheMultipleScalesModelAndPredictWithIt) {
  // Three steps around the resonance at a small force, from the simulator.
  std::ofstream(folder_ / "scenario.json") << beamid::testing::PaperScenarioJson("cli test: --model ms", R"([
    {"label": "low", "force_amplitude_N": 0.5, "frequencies_Hz": {"start": 53.6, "stop": 54.6, "step": 0.5}}])", 3);
  const std::string campaign = (folder_ / "campaign").string();
  ProgramRun run = Beamid("-q simulate " + (folder_ / "scenario.json").string() + " -o " + campaign);
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const std::string result = (folder_ / "result.json").string();
  run = Beamid("identify " + campaign + " --fit acc1,acc2 --validate acc3 --model ms --fix-loss-factor " +
               "--beam-loss-factor 2e-4 -o " + result);
  ASSERT_EQ(run.exit_code, 0) << run.output;
  EXPECT_THAT(run.output, HasSubstr("identified (multiple scales)"));
  EXPECT_THAT(ReadFile(result), HasSubstr("\"kind\": \"ms\""));
  EXPECT_THAT(ReadFile(result), HasSubstr("\"modal_phasor_m\""));
  run = Beamid("predict " + result + " --x 0.57 --campaign " + campaign + " -o " + (folder_ / "pred.json").string() +
               " --csv " + (folder_ / "pred.csv").string());
  ASSERT_EQ(run.exit_code, 0) << run.output;
  EXPECT_THAT(run.output, HasSubstr("with the multiple scales model"));
  EXPECT_THAT(ReadFile(folder_ / "pred.json"), HasSubstr("\"model\": \"ms\""));
  // Compared in the channel's own quantity (acc3 measures acceleration).
  EXPECT_THAT(ReadFile(folder_ / "pred.json"), HasSubstr("\"predicted_acceleration_m_s2\""));
  // The CSV holds the file's numbers, a row per step and harmonic.
  const beamid::solver::PredictionFile prediction = beamid::solver::ReadPredictionFile(folder_ / "pred.json");
  const std::vector<std::string> rows = beamid::testing::Lines(ReadFile(folder_ / "pred.csv"));
  ASSERT_EQ(rows.size(), 1 + prediction.steps.size() * prediction.steps.front().harmonics.size());
  const std::vector<std::string> header = beamid::testing::Cells(rows[0]);
  ASSERT_EQ(header[12], "measured_amplitude_m_s2");
  const std::vector<std::string> first = beamid::testing::Cells(rows[1]);
  ASSERT_EQ(first.size(), header.size());
  const beamid::solver::PredictionHarmonic& h1 = prediction.steps.front().harmonics.front();
  EXPECT_EQ(first[11], "acc3");
  EXPECT_EQ(first[12], beamid::testing::G9(std::abs(h1.measured)));
  EXPECT_EQ(first[14], beamid::testing::G9(std::abs(h1.predicted)));

  // The model gives harmonics 1..3 only: bad input, not a failed fit.
  run = Beamid("identify " + campaign + " --fit acc1,acc2 --model ms --fit-harmonics 5");
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_THAT(run.output, HasSubstr("fit at most 3 harmonics"));
  run = Beamid("identify " + campaign + " --fit acc1,acc2 --model duffing");
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_THAT(run.output, HasSubstr("--model: unknown model family 'duffing' (use hb, ms)"));
  // A channel fitted twice would count double.
  run = Beamid("identify " + campaign + " --fit acc1,acc1");
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_THAT(run.output, HasSubstr("channel 'acc1' is listed twice"));
  // Phasors of a subset of the campaign (here: without its last step).
  const auto phasors = folder_ / "phasors.json";
  ASSERT_EQ(Beamid("-q extract " + campaign + " -o " + phasors.string()).exit_code, 0);
  nlohmann::json subset = nlohmann::json::parse(ReadFile(phasors));
  subset["steps"].erase(subset["steps"].size() - 1);
  std::ofstream(phasors) << subset.dump();
  run = Beamid("identify " + campaign + " --fit acc1,acc2 --phasors " + phasors.string());
  EXPECT_EQ(run.exit_code, 2) << run.output;
  EXPECT_THAT(run.output, HasSubstr("these phasors are not the campaign's (2 steps against the campaign's 3"));
}

TEST_F(CommandLine, IdentifyRefitsTheDampingLawsAndWritesTheirModelFormIntervals) {
  std::ofstream(folder_ / "scenario.json") << beamid::testing::PaperScenarioJson("cli test: damping laws", R"([
    {"label": "low", "force_amplitude_N": 1.0, "frequencies_Hz": {"start": 52.5, "stop": 55.5, "step": 1.0}},
    {"label": "high", "force_amplitude_N": 9.0, "frequencies_Hz": {"start": 52.5, "stop": 55.5, "step": 1.0}}])", 5);
  const std::string campaign = (folder_ / "campaign").string();
  ASSERT_EQ(Beamid("-q simulate " + (folder_ / "scenario.json").string() + " -o " + campaign).exit_code, 0);
  const std::string result = (folder_ / "result.json").string();
  const std::string parameters_csv = (folder_ / "parameters.csv").string();
  ProgramRun run = Beamid("identify " + campaign + " --fit acc1,acc2 -o " + result + " --csv " + parameters_csv);
  ASSERT_EQ(run.exit_code, 0) << run.output;
  EXPECT_THAT(run.output, HasSubstr("beam damping laws (the fit assumes loss_factor):"));
  EXPECT_THAT(run.output, HasSubstr("total 95 % intervals: the statistical part (with the residual model error where the weighting "
                                    "estimates it), the accepted damping laws ("));
  const nlohmann::json written = nlohmann::json::parse(ReadFile(result));
  ASSERT_TRUE(written.contains("damping_laws"));
  std::vector<std::string> laws;
  for (const auto& law : written["damping_laws"]["laws"]) laws.push_back(law["law"]);
  EXPECT_EQ(laws, (std::vector<std::string>{"loss_factor", "modal_loss_factor", "rayleigh", "mass_proportional",
                                           "stiffness_proportional"}));
  std::vector<std::string> shared;
  for (const auto& interval : written["damping_laws"]["model_form_intervals"]) {
    shared.push_back(interval["name"]);
    // The envelope holds the accepted laws' intervals: never narrower than
    // the fitted law's when that law is accepted.
    if (written["damping_laws"]["laws"][0]["accepted"]) {
      const auto& p = written["parameters"][interval["name"].get<std::string>()];
      EXPECT_LE(interval["ci95"][0].get<double>(), p["ci95"][0].get<double>());
      EXPECT_GE(interval["ci95"][1].get<double>(), p["ci95"][1].get<double>());
    }
  }
  EXPECT_EQ(shared, (std::vector<std::string>{"k1", "k2", "k3", "c"}));
  // The CSV holds the file's parameters, each with its interval, and the
  // total interval for those the damping laws share (empty for the others).
  const std::vector<std::string> rows = beamid::testing::Lines(ReadFile(parameters_csv));
  ASSERT_EQ(rows.size(), 1 + written["parameters"].size());
  EXPECT_EQ(rows[0], "parameter,unit,value,std,lower_95,upper_95,std_model_error,total_lower_95,total_upper_95,"
                     "total_holds");
  for (std::size_t i = 1; i < rows.size(); ++i) {
    const std::vector<std::string> cells = beamid::testing::Cells(rows[i]);
    ASSERT_GE(cells.size(), 9u) << rows[i];
    const auto& p = written["parameters"][cells[0]];
    ASSERT_TRUE(p.is_object()) << rows[i];
    EXPECT_EQ(cells[2], beamid::testing::G9(p["value"].get<double>())) << rows[i];
    EXPECT_EQ(cells[4], beamid::testing::G9(p["ci95"][0].get<double>())) << rows[i];
    EXPECT_EQ(cells[5], beamid::testing::G9(p["ci95"][1].get<double>())) << rows[i];
    const auto total = std::find_if(written["damping_laws"]["model_form_intervals"].begin(),
                                    written["damping_laws"]["model_form_intervals"].end(),
                                    [&](const auto& m) { return m["name"] == cells[0]; });
    if (total == written["damping_laws"]["model_form_intervals"].end()) {
      EXPECT_EQ(cells[7], "") << rows[i];
      continue;
    }
    EXPECT_EQ(cells[7], beamid::testing::G9((*total)["ci95"][0].get<double>())) << rows[i];
    EXPECT_EQ(cells[8], beamid::testing::G9((*total)["ci95"][1].get<double>())) << rows[i];
    EXPECT_THAT(rows[i], HasSubstr("the accepted damping laws")) << rows[i];
  }
  // The harmonic truncation's refit (5 → 9 harmonics) is in the file, and
  // each total interval is the damping-law envelope widened by its shift.
  const auto& truncation = written["damping_laws"]["truncation"];
  EXPECT_EQ(truncation["model_harmonics"], 5);
  EXPECT_EQ(truncation["refit_harmonics"], 9);
  EXPECT_TRUE(truncation["converged"].get<bool>()) << truncation["status"];
  for (const auto& interval : written["damping_laws"]["model_form_intervals"]) {
    const double shift = std::abs(interval["truncation_shift"].get<double>());
    EXPECT_DOUBLE_EQ(interval["ci95"][0].get<double>(), interval["damping_law_ci95"][0].get<double>() - shift);
    EXPECT_DOUBLE_EQ(interval["ci95"][1].get<double>(), interval["damping_law_ci95"][1].get<double>() + shift);
  }

  // The default weighing propagates each phasor's errors.
  EXPECT_EQ(written["model"]["phasor_uncertainty"], "propagated");
  // The budget names each term: the noise, the force's and the frequency's
  // errors, and the residual model error the fit estimated per harmonic
  // (relative to the model's phasor, so within the fit's error of ε_k).
  const auto& budget = written["quality"]["acc1"]["h1"]["high"]["relative_std"];
  EXPECT_GT(budget["noise"].get<double>(), 0.0);
  EXPECT_GT(budget["force"].get<double>(), 0.0);
  EXPECT_GT(budget["frequency"].get<double>(), 0.0);
  const auto& model_errors = written["fit"]["model_errors"];
  ASSERT_EQ(model_errors.size(), 3u);
  const double epsilon_1 = model_errors[0]["relative"].get<double>();
  EXPECT_NEAR(budget["model_error"].get<double>(), epsilon_1, 0.01 * epsilon_1 + 1e-15);
  for (const auto& e : model_errors) {
    const double relative = e["relative"].get<double>();
    EXPECT_LE(e["ci95"][0].get<double>(), relative);
    EXPECT_GE(e["ci95"][1].get<double>(), relative);
    // A residual model error only where the stated σ leave an excess.
    EXPECT_EQ(relative > 0.0, e["chi_square"].get<double>() > e["degrees_of_freedom"].get<double>());
  }
  for (const auto& [name, p] : written["parameters"].items()) {
    EXPECT_GE(p["std_model_error"].get<double>(), 0.0) << name;
    EXPECT_LE(p["std_model_error"].get<double>(), p["std"].get<double>()) << name;
  }

  run = Beamid("identify " + campaign + " --fit acc1,acc2 --no-damping-laws --phasor-uncertainty relative_floor -o " +
               result);
  ASSERT_EQ(run.exit_code, 0) << run.output;
  EXPECT_THAT(run.output, ::testing::Not(HasSubstr("beam damping laws")));
  const nlohmann::json floor = nlohmann::json::parse(ReadFile(result));
  EXPECT_FALSE(floor.contains("damping_laws"));
  EXPECT_EQ(floor["model"]["phasor_uncertainty"], "relative_floor");
  // Under the floor nothing is estimated: the floor stands in for it.
  EXPECT_FALSE(floor["fit"].contains("model_errors"));
}

TEST_F(CommandLine, MeasuredBackboneRejectsABadTableNamingFileAndColumn) {
  std::ofstream(folder_ / "high.csv") << "frequency_Hz;force_N;acceleration [m/s^2];phase\n54;1;2;10\n55;1;3;80\n56;1;2;150\n";
  ProgramRun run = Beamid("backbone --measured " + (folder_ / "high.csv").string() + " -o " + (folder_ / "bb").string());
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_THAT(run.output, HasSubstr("high.csv"));
  EXPECT_THAT(run.output, HasSubstr("column 'phase'"));
  run = Beamid("backbone -o " + (folder_ / "bb").string());
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_THAT(run.output, HasSubstr("--measured"));
}

// The commands as `beamid --help` lists them: a new command is checked
// without editing this test.
std::vector<std::string> ListedCommands() {
  const ProgramRun run = Beamid("--help");
  std::vector<std::string> commands;
  std::istringstream lines(run.output.substr(run.output.find("Subcommands:")));
  std::string line;
  std::getline(lines, line);
  while (std::getline(lines, line))
    if (line.size() > 2 && line[0] == ' ' && line[1] == ' ' && line[2] != ' ')
      commands.push_back(line.substr(2, line.find(' ', 2) - 2));
  return commands;
}

TEST_F(CommandLine, EveryCommandHasHelpWithAnExample) {
  const std::vector<std::string> commands = ListedCommands();
  for (const char* expected : {"frc", "backbone", "identify", "predict", "extract", "simulate", "report", "diagnose"})
    EXPECT_NE(std::find(commands.begin(), commands.end(), expected), commands.end()) << expected;
  for (const std::string& command : commands) {
    const ProgramRun run = Beamid(command + " --help");
    EXPECT_EQ(run.exit_code, 0) << command;
    EXPECT_THAT(run.output, HasSubstr("Example")) << command;
    EXPECT_THAT(run.output, HasSubstr("beamid " + command + " ")) << command;
    EXPECT_THAT(run.output, HasSubstr("--quiet")) << command << ": the global options are listed";
    EXPECT_THAT(run.output, HasSubstr("--progress")) << command;
  }
}

const std::string kShortFrc = "frc examples/paper_setup/model.json --force-N 1 --from-hz 53 --to-hz 56 -o ";

TEST_F(CommandLine, QuietPrintsNothingBeforeOrAfterTheCommandName) {
  for (const std::string& arguments : {"-q " + kShortFrc + (folder_ / "a").string(),
                                       kShortFrc + (folder_ / "b").string() + " --quiet"}) {
    const ProgramRun run = Beamid(arguments);
    EXPECT_EQ(run.exit_code, 0) << run.output;
    EXPECT_EQ(run.output, "") << arguments;
  }
  EXPECT_TRUE(std::filesystem::exists(folder_ / "b.json"));
}

// Each line of stderr parses as one JSON object; progress fractions rise to
// 1, each task ends with "done", and the last line gives the exit code.
std::vector<nlohmann::json> JsonLines(const std::string& text) {
  std::vector<nlohmann::json> lines;
  std::istringstream stream(text);
  std::string line;
  while (std::getline(stream, line)) {
    EXPECT_NO_THROW(lines.push_back(nlohmann::json::parse(line))) << "not JSON: " << line;
  }
  return lines;
}

TEST_F(CommandLine, ProgressJsonIsOneObjectPerLineOnStderr) {
  const ProgramRun run = Beamid(kShortFrc + (folder_ / "frc").string() + " --progress json", /*stderr_only=*/true);
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const std::vector<nlohmann::json> lines = JsonLines(run.output);
  ASSERT_GE(lines.size(), 5u) << run.output;
  double last_fraction = -1.0;
  int done = 0;
  for (const auto& line : lines) {
    if (line.at("event") == "progress") {
      EXPECT_GT(line.at("fraction").get<double>(), last_fraction);
      EXPECT_LE(line.at("fraction").get<double>(), 1.0);
      last_fraction = line.at("fraction").get<double>();
      EXPECT_THAT(line.at("task").get<std::string>(), HasSubstr("frc"));
    }
    if (line.at("event") == "done") ++done;
  }
  EXPECT_GT(last_fraction, 0.9);
  EXPECT_EQ(done, 1);
  EXPECT_EQ(lines.back().at("event"), "exit");
  EXPECT_EQ(lines.back().at("exit_code"), 0);
}

TEST_F(CommandLine, ExitCodesTellBadInputFromFailureToConverge) {
  // Bad command lines are bad input, like bad files.
  EXPECT_EQ(Beamid("frc examples/paper_setup/model.json --no-such-option").exit_code, 2);
  EXPECT_EQ(Beamid("--progress xml frc examples/paper_setup/model.json").exit_code, 2);
  EXPECT_EQ(Beamid("report " + (folder_ / "missing.json").string()).exit_code, 2);
  // A continuation allowed five points cannot cross the range: it fails to
  // converge (3), writes what it has, and says so in JSON too.
  const ProgramRun run = Beamid("frc examples/paper_setup/model.json --force-N 1 --from-hz 50 --to-hz 58 "
                                "--max-points 5 --progress json -q -o " + (folder_ / "short").string(),
                                /*stderr_only=*/true);
  EXPECT_EQ(run.exit_code, 3) << run.output;
  EXPECT_TRUE(std::filesystem::exists(folder_ / "short.json"));
  const std::vector<nlohmann::json> lines = JsonLines(run.output);
  ASSERT_FALSE(lines.empty());
  EXPECT_EQ(lines.back().at("exit_code"), 3);
  EXPECT_THAT(lines.back().at("message").get<std::string>(), HasSubstr("stopped early"));
}

// On a terminal (a pseudo-terminal from script(1)) progress rewrites one
// line in place and ends with "done".
TEST_F(CommandLine, ProgressOnATerminalRewritesOneLine) {
  if (std::system("command -v script > /dev/null 2>&1") != 0) GTEST_SKIP() << "script(1) is not installed";
  const auto log = folder_ / "tty.log";
  const std::string command = "script -qec \"" + std::string(BEAMID_EXECUTABLE) + " " + kShortFrc +
                              (folder_ / "tty").string() + "\" /dev/null > " + log.string() + " 2>&1 < /dev/null";
  ASSERT_EQ(std::system(command.c_str()), 0);
  const std::string output = ReadFile(log);
  EXPECT_THAT(output, HasSubstr("\rfrc: level 1/1 (1 N)"));
  EXPECT_THAT(output, HasSubstr(" %"));
  EXPECT_THAT(output, HasSubstr("done"));
}

}  // namespace
