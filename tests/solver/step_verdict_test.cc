// The verdict on a step of a running test: measured again when unsettled
// or noisy, a jump said, and the record length that reaches a target σ —
// the last checked on the simulator's recordings, whose noise the 1/√T
// rule must predict for a record it has not seen.
#include "solver/live/step_verdict.h"

#include <cmath>
#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "hb/errors.h"
#include "hb/scenario.h"
#include "signal/campaign.h"
#include "signal/phasor_estimator.h"
#include "signal/recording.h"
#include "tests/support/paper_scenario.h"
#include "tests/support/simulated_campaign.h"
#include "tests/support/temp_path.h"

namespace beamid::solver {
namespace {

signal::ChannelPhasors Channel(const std::string& name, double amplitude, double sigma, double snr_db) {
  signal::ChannelPhasors channel;
  channel.channel = name;
  channel.snr_db = snr_db;
  channel.harmonics.push_back({.harmonic = 1, .value = {amplitude, 0.0}, .std_real = sigma, .std_imag = sigma});
  return channel;
}

signal::StepPhasors Step(double frequency_hz, double acc1, double acc2) {
  signal::StepPhasors step;
  step.level = "low";
  step.nominal_frequency_hz = frequency_hz;
  step.responses = {Channel("acc1", acc1, 1e-3, 60.0), Channel("acc2", acc2, 1e-2, 45.0)};
  step.quality.analysed_duration_s = 0.5;
  step.quality.settled_after_s = 0.1;
  return step;
}

TEST(StepVerdictTest, TheWorstAnalysedChannelSetsTheRecordAndAJumpIsSaid) {
  const signal::StepPhasors step = Step(52.0, 1.0, 2.0);
  StepVerdict v = JudgeStep(step, {}, {.target_relative_std = 1e-3, .max_record_s = 20.0});
  EXPECT_FALSE(v.measure_again);
  EXPECT_EQ(v.worst_channel, "acc2");  // 1e-2/2 against 1e-3/1
  EXPECT_DOUBLE_EQ(v.relative_std, 5e-3);
  EXPECT_DOUBLE_EQ(v.snr_db, 45.0);
  EXPECT_NEAR(v.record_needed_s, 0.5 * 25.0, 1e-12) << "T·(r/r*)²";
  EXPECT_NEAR(v.extra_settle_s, 1.5 * 0.1, 1e-12);
  // acc1 alone analysed: its r is the target's, the record stays 0.5 s.
  v = JudgeStep(step, {"acc1"}, {.target_relative_std = 1e-3});
  EXPECT_EQ(v.worst_channel, "acc1");
  EXPECT_NEAR(v.record_needed_s, 0.5, 1e-12);
  EXPECT_DOUBLE_EQ(v.snr_db, 60.0);
  // A record's length is clamped to the range the options allow.
  EXPECT_DOUBLE_EQ(JudgeStep(step, {}, {.target_relative_std = 1e-4, .max_record_s = 5.0}).record_needed_s, 5.0);
  // The fundamental doubled since the step before: a jump.
  const signal::StepPhasors before = Step(51.9, 0.45, 1.0);
  v = JudgeStep(step, {}, {}, &before);
  ASSERT_EQ(v.warnings.size(), 2u);
  EXPECT_NE(v.warnings[0].find("jump"), std::string::npos) << v.warnings[0];
  EXPECT_TRUE(JudgeStep(step, {}, {}, &step).warnings.empty());
  // 1 Hz apart, a resonance alone may grow that much: no jump said.
  const signal::StepPhasors far = Step(51.0, 0.45, 1.0);
  EXPECT_TRUE(JudgeStep(step, {}, {}, &far).warnings.empty());
}

TEST(StepVerdictTest, UnsettledStepsAreMeasuredAgainWithALongerSettleAndNoisyOnesWarned) {
  signal::StepPhasors step = Step(52.0, 1.0, 2.0);
  step.quality.unsettled = true;
  step.quality.unsettled_channel = "acc1";
  step.quality.unsettled_change_relative = 0.02;
  StepVerdict v = JudgeStep(step, {}, {});
  EXPECT_TRUE(v.measure_again);
  ASSERT_EQ(v.reasons.size(), 1u);
  EXPECT_NE(v.reasons[0].find("not settled"), std::string::npos);
  EXPECT_NEAR(v.extra_settle_s, 1.5 * (0.1 + 0.5), 1e-12) << "the whole record was transient";
  step.quality.unsettled = false;
  v = JudgeStep(step, {}, {.min_snr_db = 50.0});
  EXPECT_FALSE(v.measure_again);
  ASSERT_EQ(v.warnings.size(), 1u);
  EXPECT_NE(v.warnings[0].find("SNR 45.0 dB"), std::string::npos) << v.warnings[0];
  EXPECT_TRUE(JudgeStep(step, {"acc1"}, {.min_snr_db = 50.0}).warnings.empty()) << "acc2 is not analysed";
  EXPECT_TRUE(JudgeStep(step, {"acc3"}, {}).measure_again) << "no analysed channel in the record";
  EXPECT_THROW(JudgeStep(step, {}, {.target_relative_std = 0.0}), InputError);
}

// One step of the paper's beam at 40 Hz recorded for record_s, extracted.
signal::StepPhasors SimulatedStep(double record_s, int seed) {
  const std::filesystem::path folder = beamid::testing::UniqueTempPath("beamid_verdict_" + std::to_string(seed));
  std::filesystem::remove_all(folder);
  std::string json = beamid::testing::PaperScenarioJson(
      "verdict", R"([{"label": "low", "force_amplitude_N": 1, "frequencies_Hz": [40]}])", seed);
  const std::string record = "\"record_s\": 0.4";
  json.replace(json.find(record), record.size(), "\"record_s\": " + std::to_string(record_s));
  const hb::Scenario scenario = hb::ParseScenario(json, "verdict.json");
  beamid::testing::SimulateInto(scenario, folder);
  const signal::Campaign campaign = signal::ReadCampaign(folder);
  const signal::StepPhasors step = signal::EstimateStepPhasors(signal::ReadRecording(campaign, campaign.steps[0]),
                                                               campaign, campaign.steps[0]);
  std::filesystem::remove_all(folder);
  return step;
}

TEST(StepVerdictTest, TheRecordItAsksForReachesTheTargetOnTheSimulatorsNoise) {
  const signal::StepPhasors short_step = SimulatedStep(0.25, 11);
  const StepVerdict first = JudgeStep(short_step, {}, {.target_relative_std = 1.0});
  // Ask for a third of the σ the short record gave: a record ~9 times longer.
  const double target = first.relative_std / 3.0;
  const StepVerdict asked = JudgeStep(short_step, {}, {.target_relative_std = target});
  EXPECT_GT(asked.record_needed_s, 6.0 * first.analysed_s);
  EXPECT_LT(asked.record_needed_s, 12.0 * first.analysed_s);
  const signal::StepPhasors long_step = SimulatedStep(asked.record_needed_s, 12);
  const StepVerdict reached = JudgeStep(long_step, {}, {.target_relative_std = target});
  EXPECT_LT(reached.relative_std, 1.3 * target) << "short: " << first.relative_std << " over " << first.analysed_s
                                                << " s; long: " << reached.relative_std << " over "
                                                << reached.analysed_s << " s";
  EXPECT_GT(reached.relative_std, 0.7 * target);
}

}  // namespace
}  // namespace beamid::solver
