// The test guided while it runs, in closed loop with the time-domain
// simulator as the rig (hb/virtual_rig.h) on the paper's set-up: the watch
// plans each step, the rig runs it and writes it into the folder, the watch
// reads it like any acquisition's. The loop must stop by itself with k1, k3
// and c at their target σ and the truth inside their intervals, having
// read every step the rig wrote exactly once, and most of its steps near
// resonance, where the uniform sweep spends few.
#include <cmath>
#include <filesystem>
#include <map>
#include <string>

#include <gtest/gtest.h>

#include "hb/text_file.h"
#include "solver/live/test_plan_io.h"
#include "solver/workflow/watch_campaign.h"
#include "tests/support/paper_scenario.h"
#include "tests/support/temp_path.h"

namespace beamid::workflow {
namespace {

namespace fs = std::filesystem;

TEST(ClosedLoopTest, ReachesTheTargetPrecisionWithTheTruthInsideAndStopsByItself) {
  const fs::path root = beamid::testing::UniqueTempPath("beamid_closed_loop");
  fs::remove_all(root);
  fs::create_directories(root);
  WriteTextFileAtomically(
      root / "scenario.json",
      beamid::testing::PaperScenarioJson("closed loop", R"([
        {"label": "low", "force_amplitude_N": 1, "frequencies_Hz": {"start": 50, "stop": 58, "step": 0.25}},
        {"label": "high", "force_amplitude_N": 9, "frequencies_Hz": {"start": 50, "stop": 58, "step": 0.25}}])",
                                         5));
  WatchRequest request{.campaign_folder = (root / "campaign").string(),
                       .plan_file = (root / "plan.json").string(),
                       .virtual_rig = (root / "scenario.json").string()};
  request.live.planner = {.levels = {{.label = "low", .force_N = 1.0}, {.label = "high", .force_N = 9.0}},
                          .band_low_hz = 50.0,
                          .band_high_hz = 58.0,
                          .target_relative_std = 0.002,
                          .max_steps = 80};
  std::map<std::string, int> analysed;  // by file
  const WatchOutcome outcome =
      WatchCampaign(request, {}, [&](const solver::LiveUpdate& update) { ++analysed[update.file]; });
  const solver::TestPlan& plan = outcome.plan;
  ASSERT_TRUE(plan.done);
  EXPECT_NE(plan.done_reason.find("target"), std::string::npos) << plan.done_reason;
  EXPECT_EQ(outcome.steps_handed_out, outcome.rig_steps);
  for (const auto& [file, times] : analysed) EXPECT_EQ(times, 1) << file;
  const std::map<std::string, double> truth{{"k1", 150.0}, {"k3", 3e5}, {"c", 0.05}};
  for (const solver::PlanParameter& p : plan.parameters) {
    if (!truth.contains(p.name)) continue;
    EXPECT_LE(p.std, p.target_std) << p.name;
    EXPECT_LT(std::abs(p.value - truth.at(p.name)), 3.0 * p.std) << p.name << " = " << p.value << " ± " << p.std;
  }
  EXPECT_EQ(solver::ReadTestPlan(request.plan_file).sequence, plan.sequence);
  // Where the steps went: within ±0.5 Hz of each level's largest response
  // (acc3), against the uniform grid's 0.25 Hz spacing, which puts 5 of its
  // 33 steps there.
  std::map<std::string, std::pair<double, double>> peak;  // level: (|X1|, f)
  for (const signal::StepPhasors& step : outcome.phasors.steps) {
    const double amplitude = step.Find("acc3")->Harmonic(1).Amplitude();
    if (amplitude > peak[step.level].first) peak[step.level] = {amplitude, step.nominal_frequency_hz};
  }
  int near_resonance = 0;
  for (const signal::StepPhasors& step : outcome.phasors.steps)
    if (std::abs(step.nominal_frequency_hz - peak[step.level].second) <= 0.5) ++near_resonance;
  const int usable = static_cast<int>(outcome.phasors.steps.size());
  EXPECT_GT(near_resonance, usable / 2) << "of " << usable << " usable steps";
  EXPECT_LT(outcome.rig_steps, 40);
  std::printf("closed loop: %d steps (%d usable, %d within 0.5 Hz of a level's peak), rig time %.1f s\n",
              outcome.rig_steps, usable, near_resonance, outcome.rig_time_s);
  fs::remove_all(root);
}

}  // namespace
}  // namespace beamid::workflow
