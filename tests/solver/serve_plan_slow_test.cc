// The loop closed across two processes, as at a rig: `beamid simulate
// --serve PLAN` runs each step the plan file asks for and writes it into
// the campaign folder, while `beamid watch` follows that folder in real
// time and rewrites the plan. Both must finish by themselves, the watch
// with its targets reached and the rig told the plan is done.
#include <filesystem>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "signal/campaign.h"
#include "solver/report/external_program.h"
#include "solver/live/test_plan_io.h"
#include "tests/support/file_bytes.h"
#include "tests/support/paper_scenario.h"
#include "tests/support/temp_path.h"

namespace beamid::solver {
namespace {

namespace fs = std::filesystem;
using beamid::testing::ProgramRun;
using beamid::testing::ReadFile;

ProgramRun Beamid(const std::vector<std::string>& arguments, const fs::path& log) {
  const int status = RunExternalProgram({.program = BEAMID_EXECUTABLE,
                                         .arguments = arguments,
                                         .debian_package = "(the beamid build)",
                                         .stdout_file = log,
                                         .stderr_file = log.string() + ".err"});
  return {status, ReadFile(log) + ReadFile(log.string() + ".err")};
}

TEST(ServePlan, TheRigAndTheWatchCloseTheLoopAcrossTwoProcesses) {
  const fs::path root = beamid::testing::UniqueTempPath("beamid_serve");
  fs::remove_all(root);
  fs::create_directories(root);
  beamid::testing::WriteFile(root / "scenario.json", beamid::testing::PaperScenarioJson("serve", R"([
      {"label": "low", "force_amplitude_N": 1, "frequencies_Hz": [50]},
      {"label": "high", "force_amplitude_N": 9, "frequencies_Hz": [50]}])",
                                                                                    5));
  const std::string campaign = (root / "campaign").string(), plan = (root / "plan.json").string();
  fs::create_directories(campaign);  // the watch follows a folder that exists
  ProgramRun rig;
  std::thread serve([&] {
    rig = Beamid({"simulate", (root / "scenario.json").string(), "-o", campaign, "--serve", plan, "--poll", "0.05",
                  "--idle-timeout", "120"},
                 root / "serve.log");
  });
  const ProgramRun watch = Beamid({"watch", campaign, "--level", "low=1", "--level", "high=9", "--band", "50", "58",
                                   "--plan", plan, "--poll", "0.05", "--stable", "0.2", "--idle-timeout", "120"},
                                  root / "watch.log");
  serve.join();
  EXPECT_EQ(watch.exit_code, 0) << watch.output;
  EXPECT_EQ(rig.exit_code, 0) << rig.output;
  EXPECT_NE(watch.output.find("done: every target parameter has reached its σ"), std::string::npos) << watch.output;
  EXPECT_NE(rig.output.find("the plan is done"), std::string::npos) << rig.output;
  const TestPlan last = ReadTestPlan(plan);
  ASSERT_TRUE(last.done);
  // Every step the rig wrote was analysed, and none twice.
  const signal::Campaign written = signal::ReadCampaign(campaign);
  EXPECT_EQ(static_cast<int>(written.steps.size()), last.steps_analysed);
  EXPECT_GE(last.steps_analysed, 5);

  // The rig refuses a plan file inside the folder it writes.
  const ProgramRun refused = Beamid({"simulate", (root / "scenario.json").string(), "-o", (root / "other").string(),
                                     "--serve", (root / "other/plan.json").string()},
                                    root / "refused.log");
  EXPECT_EQ(refused.exit_code, 2) << refused.output;
  fs::remove_all(root);
}

}  // namespace
}  // namespace beamid::solver
