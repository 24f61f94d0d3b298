// The beamid program itself: each command runs from a clean folder, writes
// what it says, and bad input ends with exit code 2 and a message naming
// the file and what to fix.
#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "tests/support/temp_path.h"

namespace {

using ::testing::HasSubstr;

struct ProgramRun {
  int exit_code = -1;
  std::string output;  // stdout and stderr
};

ProgramRun Beamid(const std::string& arguments) {
  const auto log = beamid::testing::UniqueTempPath("beamid_cli_test") += ".log";
  const std::string command = std::string(BEAMID_EXECUTABLE) + " " + arguments + " > " + log.string() + " 2>&1";
  const int status = std::system(command.c_str());
  std::ifstream in(log);
  std::stringstream text;
  text << in.rdbuf();
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, text.str()};
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
    "youngs_modulus_Pa": 2.1e11, "density_kg_m3": 7850}, "support": {"polynomial": {"k1": 150}},
    "excitation": {"position_m": 0.57}})";
  run = Beamid("backbone " + (folder_ / "typo.json").string());
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_THAT(run.output, HasSubstr("unknown field 'k1'"));
  run = Beamid("identify " + (folder_ / "no_campaign").string() + " --fit acc1");
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_THAT(run.output, HasSubstr("no_campaign"));
  run = Beamid("frc examples/paper_setup/model.json --harmonics 0");
  EXPECT_EQ(run.exit_code, 2);
  run = Beamid("diagnose " + (folder_ / "no_campaign").string() + " --candidates gravity");
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_THAT(run.output, HasSubstr("gravity"));
}

TEST_F(CommandLine, EveryCommandHasHelpWithAnExample) {
  for (const char* command : {"frc", "backbone", "identify", "predict", "extract", "simulate", "diagnose"}) {
    const ProgramRun run = Beamid(std::string(command) + " --help");
    EXPECT_EQ(run.exit_code, 0) << command;
    EXPECT_THAT(run.output, HasSubstr("Example")) << command;
    EXPECT_THAT(run.output, HasSubstr("beamid " + std::string(command) + " ")) << command;
  }
}

}  // namespace
