// `beamid watch`'s loop on an acquisition written by hand: the first plan is
// there before any step, a faulty step is asked for again (the same level
// and frequency, flagged as a repeat) and, rewritten, used; the plan file
// on disk is always the last plan, whole.
#include "solver/workflow/watch_campaign.h"

#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "hb/errors.h"
#include "hb/scenario.h"
#include "solver/live/test_plan_io.h"
#include "tests/support/file_bytes.h"
#include "tests/support/paper_scenario.h"
#include "tests/support/simulated_campaign.h"
#include "tests/support/temp_path.h"

namespace beamid::workflow {
namespace {

namespace fs = std::filesystem;

void WriteFile(const fs::path& path, const std::string& text) {
  fs::create_directories(path.parent_path());
  beamid::testing::WriteFile(path, text);
}

TEST(WatchCampaignTest, AFaultyStepIsAskedForAgainAndThePlanFileIsTheLastPlan) {
  const fs::path root = beamid::testing::UniqueTempPath("beamid_watch");
  fs::remove_all(root);
  const fs::path source = root / "source", live = root / "live", plan_file = root / "plan.json";
  const hb::Scenario scenario = hb::ParseScenario(
      beamid::testing::PaperScenarioJson(
          "watch", R"([{"label": "low", "force_amplitude_N": 1, "frequencies_Hz": [40, 41]}])", 3),
      "watch.json");
  beamid::testing::SimulateInto(scenario, source);
  fs::create_directories(live);
  WatchRequest request{.campaign_folder = live.string(), .plan_file = plan_file.string()};
  request.follower.stable_s = 0.5;
  request.live.planner = {.levels = {{.label = "low", .force_N = 1.0}}, .band_low_hz = 40.0, .band_high_hz = 45.0};
  CampaignWatch watch(request);
  ASSERT_TRUE(watch.plan().next.has_value()) << "the first step is planned before the acquisition starts";
  EXPECT_DOUBLE_EQ(watch.plan().next->frequency_hz, 40.0);
  EXPECT_EQ(solver::ReadTestPlan(plan_file).sequence, watch.plan().sequence);

  WriteFile(live / "campaign.json", beamid::testing::ReadFile(source / "campaign.json"));
  const std::string step0 = beamid::testing::ReadFile(source / "low/step_000.csv");
  WriteFile(live / "low/step_000.csv", step0.substr(0, step0.size() / 40));  // a record cut short
  EXPECT_TRUE(watch.Poll(0.0).empty());
  std::vector<solver::LiveUpdate> updates = watch.Poll(1.0);
  ASSERT_EQ(updates.size(), 1u);
  EXPECT_FALSE(updates[0].usable);
  EXPECT_FALSE(updates[0].error.empty());
  ASSERT_TRUE(watch.plan().next.has_value());
  EXPECT_TRUE(watch.plan().next->repeat);
  EXPECT_DOUBLE_EQ(watch.plan().next->frequency_hz, 40.0);
  EXPECT_EQ(watch.plan().next->level, "low");
  EXPECT_NE(watch.plan().next->reason.find("low/step_000.csv"), std::string::npos) << watch.plan().next->reason;
  const solver::TestPlan on_disk = solver::ReadTestPlan(plan_file);
  EXPECT_EQ(on_disk.sequence, watch.plan().sequence);
  EXPECT_TRUE(on_disk.next->repeat);

  WriteFile(live / "low/step_000.csv", step0);  // measured again
  WriteFile(live / "low/step_001.csv", beamid::testing::ReadFile(source / "low/step_001.csv"));
  EXPECT_TRUE(watch.Poll(2.0).empty());
  updates = watch.Poll(3.0);
  ASSERT_EQ(updates.size(), 2u);
  EXPECT_TRUE(updates[0].usable) << updates[0].error;
  EXPECT_TRUE(updates[1].usable) << updates[1].error;
  EXPECT_EQ(watch.analysis().phasors().steps.size(), 2u);
  // Too few steps to fit: the plan sweeps on from the last one.
  ASSERT_TRUE(watch.plan().next.has_value());
  EXPECT_FALSE(watch.plan().next->repeat);
  EXPECT_DOUBLE_EQ(watch.plan().next->frequency_hz, 42.0);
  EXPECT_EQ(solver::ReadTestPlan(plan_file).sequence, watch.plan().sequence);
  EXPECT_TRUE(watch.Poll(4.0).empty()) << "nothing is analysed twice";
  fs::remove_all(root);
}

TEST(WatchCampaignTest, RefusesAPlanFileInsideTheCampaignFolderAndAPlanFileThatIsNoPlan) {
  const fs::path root = beamid::testing::UniqueTempPath("beamid_watch_refused");
  fs::create_directories(root / "live");
  WatchRequest request{.campaign_folder = (root / "live").string(), .plan_file = (root / "live/plan.json").string()};
  request.live.planner = {.levels = {{.label = "low", .force_N = 1.0}}, .band_low_hz = 40.0, .band_high_hz = 45.0};
  EXPECT_THROW(CampaignWatch{request}, InputError);
  WriteFile(root / "bad_plan.json", R"({"format": "beamid-test-plan/1", "sequence": 1})");
  EXPECT_THROW(solver::ReadTestPlan(root / "bad_plan.json"), InputError);
  fs::remove_all(root);
}

}  // namespace
}  // namespace beamid::workflow
