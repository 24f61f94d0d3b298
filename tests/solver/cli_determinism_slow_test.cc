// Results must not depend on the run: `beamid identify` and `beamid diagnose`
// give identical numbers on two runs and with one thread or worker instead
// of one per core (parallel starts and refits are collected in a fixed order,
// never in the order they finish). Only the timing fields may differ.
#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "tests/support/paper_scenario.h"
#include "tests/support/temp_path.h"

namespace {

namespace fs = std::filesystem;

int Beamid(const std::string& arguments, const fs::path& log) {
  const std::string command = std::string(BEAMID_EXECUTABLE) + " " + arguments + " > " + log.string() + " 2>&1";
  const int status = std::system(command.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

std::string ReadFile(const fs::path& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// The file without its timing fields (any key holding "seconds").
nlohmann::json WithoutTimings(nlohmann::json j) {
  if (j.is_object()) {
    nlohmann::json out = nlohmann::json::object();
    for (auto& [key, value] : j.items())
      if (key.find("seconds") == std::string::npos) out[key] = WithoutTimings(value);
    return out;
  }
  if (j.is_array())
    for (auto& value : j) value = WithoutTimings(value);
  return j;
}

class Determinism : public ::testing::Test {
 protected:
  void SetUp() override {
    folder_ = beamid::testing::UniqueTempPath("beamid_determinism");
    fs::remove_all(folder_);
    fs::create_directories(folder_);
    std::ofstream(folder_ / "scenario.json") << beamid::testing::PaperScenarioJson("determinism", R"([
      {"label": "low", "force_amplitude_N": 0.5, "frequencies_Hz": {"start": 53.2, "stop": 55.2, "step": 0.4}},
      {"label": "high", "force_amplitude_N": 2.0, "frequencies_Hz": {"start": 53.6, "stop": 56.0, "step": 0.4}}])", 11);
    ASSERT_EQ(Beamid("-q simulate " + (folder_ / "scenario.json").string() + " -o " + campaign().string(), log()), 0)
        << ReadFile(log());
  }
  void TearDown() override { fs::remove_all(folder_); }

  fs::path campaign() const { return folder_ / "campaign"; }
  fs::path log() const { return folder_ / "run.log"; }

  // Runs the command three times (default parallelism twice, then `serial`)
  // and expects the same file each time, timings aside.
  void ExpectSameNumbers(const std::string& command, const std::string& serial) {
    std::string first;
    for (const std::string& extra : {std::string(), std::string(), serial}) {
      const fs::path output = folder_ / "out.json";
      ASSERT_EQ(Beamid("-q " + command + " " + extra + " -o " + output.string(), log()), 0) << ReadFile(log());
      const std::string numbers = WithoutTimings(nlohmann::json::parse(ReadFile(output))).dump(1);
      if (first.empty())
        first = numbers;
      else
        EXPECT_EQ(numbers, first) << command << " " << extra;
    }
  }

  fs::path folder_;
};

TEST_F(Determinism, IdentifyGivesTheSameNumbersOnEveryRunAndWithOneWorker) {
  ExpectSameNumbers("identify " + campaign().string() + " --fit acc1,acc2 --validate acc3 --starts 5", "--workers 1");
}

TEST_F(Determinism, DiagnoseGivesTheSameNumbersOnEveryRunAndWithOneWorker) {
  ExpectSameNumbers("diagnose " + campaign().string() + " --fit acc1,acc2 --validate acc3", "--workers 1");
}

}  // namespace
