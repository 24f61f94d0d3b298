// The simulator one step at a time, as a rig serves the step a live test
// asks for (SteppedSineSimulation::Step): run in the scenario's order it is
// the whole run sample for sample; the beam's state carries over, so a
// level the test comes back to numbers its steps on; and a campaign written
// live lists, after each step, exactly the steps whose files are whole, a
// campaign signal's strict reader accepts at every moment.
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "hb/campaign_writer.h"
#include "hb/scenario.h"
#include "hb/stepped_sine.h"
#include "signal/campaign.h"
#include "tests/support/temp_path.h"

namespace beamid::hb {
namespace {

const std::string kScenario = R"({
  "name": "stepwise",
  "beam": {"length_m": 0.6, "width_m": 0.04, "thickness_m": 0.005, "youngs_modulus_Pa": 2.1e11,
           "density_kg_m3": 7850, "loss_factor": 0.004},
  "support": {"polynomial": {"k1_Nm_rad": 150, "k3_Nm_rad3": 3e5, "c_Nms_rad": 0.2}},
  "excitation": {"channel": "F", "position_m": 0.57},
  "sensors": [{"channel": "acc1", "position_m": 0.1}, {"channel": "acc3", "position_m": 0.57}],
  "levels": [{"label": "low", "force_amplitude_N": 0.5, "frequencies_Hz": [52.0, 53.0, 54.0]},
             {"label": "high", "force_amplitude_N": 3.0, "frequencies_Hz": [55.0, 54.0]}],
  "timing": {"sample_rate_Hz": 4096, "settle_min_s": 0.1, "settle_max_s": 0.4, "transient_s": 0.03, "record_s": 0.25},
  "noise": {"seed": 3, "clock_offset_ppm": 100, "default": {"relative_rms": 0.002, "absolute": 0.002}}
})";

TEST(StepwiseSimulation, StepsInTheScenariosOrderAreTheWholeRunSampleForSample) {
  const Scenario scenario = ParseScenario(kScenario, "stepwise");
  std::vector<SimulatedStep> whole;
  SteppedSineSimulation(scenario).Run([&](const SimulatedStep& step) { whole.push_back(step); });
  SteppedSineSimulation stepwise(scenario);
  std::size_t i = 0;
  for (const ScenarioLevel& level : scenario.levels)
    for (const double frequency_hz : level.frequencies_hz) {
      const SimulatedStep step = stepwise.Step(level, frequency_hz, scenario.timing);
      ASSERT_LT(i, whole.size());
      EXPECT_EQ(step.file, whole[i].file);
      EXPECT_EQ(step.index, whole[i].index);
      EXPECT_EQ(step.level_index, whole[i].level_index);
      EXPECT_EQ(step.settle_s, whole[i].settle_s) << step.file;
      ASSERT_EQ(step.recording.rows(), whole[i].recording.rows());
      EXPECT_EQ((step.recording - whole[i].recording).cwiseAbs().maxCoeff(), 0.0) << step.file;
      ++i;
    }
  EXPECT_EQ(i, whole.size());
}

TEST(StepwiseSimulation, TheStateCarriesOverAndALevelComeBackToNumbersItsStepsOn) {
  const Scenario scenario = ParseScenario(kScenario, "stepwise");
  SteppedSineSimulation rig(scenario);
  ScenarioTiming longer = scenario.timing;
  longer.record_s = 0.5;
  const SimulatedStep a = rig.Step(scenario.levels[0], 53.0, scenario.timing);
  const SimulatedStep b = rig.Step(scenario.levels[1], 55.0, longer);
  const SimulatedStep c = rig.Step(scenario.levels[0], 53.0, scenario.timing);
  EXPECT_EQ(a.file, "low/step_000.csv");
  EXPECT_EQ(b.file, "high/step_000.csv");
  EXPECT_EQ(c.file, "low/step_001.csv");
  EXPECT_EQ(c.level_index, a.level_index);
  EXPECT_EQ(b.level_index, 1);
  EXPECT_EQ(c.index, 2);
  // The record's length is the step's own timing.
  EXPECT_EQ(b.recording.rows() - b.transient_samples, 2 * (a.recording.rows() - a.transient_samples));
  // A level that starts again starts from rest: the same step as the first time, sample for sample.
  EXPECT_EQ((c.recording - a.recording).cwiseAbs().maxCoeff(), 0.0);
  // Without the restart the beam goes on from the last step's motion: another record.
  Scenario continuing = scenario;
  continuing.timing.restart_each_level = false;
  SteppedSineSimulation carried(continuing);
  carried.Step(continuing.levels[0], 53.0, continuing.timing);
  carried.Step(continuing.levels[1], 55.0, continuing.timing);
  const SimulatedStep d = carried.Step(continuing.levels[0], 53.0, continuing.timing);
  EXPECT_GT((d.recording - a.recording).cwiseAbs().maxCoeff(), 1e-6 * a.recording.cwiseAbs().maxCoeff());
  ScenarioTiming other_rate = scenario.timing;
  other_rate.sample_rate_hz = 8192;
  EXPECT_THROW(rig.Step(scenario.levels[0], 53.0, other_rate), std::invalid_argument);
}

TEST(StepwiseSimulation, ALiveCampaignListsTheStepsWrittenSoFarAndReadsAfterEachStep) {
  const Scenario scenario = ParseScenario(kScenario, "stepwise");
  const std::filesystem::path folder = beamid::testing::UniqueTempPath("beamid_live_campaign");
  std::filesystem::remove_all(folder);
  SteppedSineSimulation rig(scenario);
  CampaignWriter writer(rig, folder, {.live = true});
  EXPECT_FALSE(std::filesystem::exists(folder / "campaign.json"));
  const std::vector<std::pair<int, double>> plan = {{1, 55.0}, {1, 54.5}, {0, 53.0}};
  for (std::size_t n = 0; n < plan.size(); ++n) {
    writer.Write(rig.Step(scenario.levels[static_cast<std::size_t>(plan[n].first)], plan[n].second,
                          scenario.timing));
    const signal::Campaign campaign = signal::ReadCampaign(folder);
    ASSERT_EQ(campaign.steps.size(), n + 1);
    EXPECT_EQ(campaign.steps.back().frequency_hz, plan[n].second);
    for (const signal::Step& step : campaign.steps) EXPECT_TRUE(std::filesystem::is_regular_file(folder / step.file));
  }
  writer.Finish();
  EXPECT_EQ(signal::ReadCampaign(folder).steps.size(), plan.size());
  EXPECT_TRUE(std::filesystem::exists(folder / "truth.json"));
  std::filesystem::remove_all(folder);
}

}  // namespace
}  // namespace beamid::hb
