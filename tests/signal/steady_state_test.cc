// Steady-state detection: a record whose first 20 % is a decaying transient
// gives the same phasors as its steady part alone (noise-free and noisy),
// records without transient keep every sample, and a record that never
// settles is rejected naming the file.
#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "signal/input_error.h"
#include "signal/phasor_estimator.h"
#include "signal/steady_state.h"
#include "tests/signal/synthetic_signal.h"

namespace beamid::signal {
namespace {

using testing::RandomTone;
using testing::Synthesize;
using testing::SyntheticCampaign;
using testing::SyntheticRecording;
using testing::Tone;

constexpr double kRateHz = 5120.0;
constexpr int kSamples = 5120;          // 1 s
constexpr double kFrequencyHz = 47.31;  // 47.31 periods: not an integer
constexpr double kNaturalHz = 61.7;     // the transient's free vibration
constexpr int kSensors = 3;

// Steady multi-harmonic response of every channel plus, when decay_s > 0, a
// free vibration e^{−t/decay}·sin(2π f_n t) as large as the steady
// amplitude at t = 0, and white noise of standard deviation noise_rel·amplitude.
Eigen::MatrixXd Record(double decay_s, double noise_rel, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> normal;
  Eigen::MatrixXd samples(kSamples, kSensors + 1);
  for (int c = 0; c <= kSensors; ++c) {
    const double amplitude = std::pow(10.0, c - 1.0);
    Tone tone = RandomTone(rng, 5, kFrequencyHz, amplitude);
    tone.sample_rate_hz = kRateHz;
    samples.col(c) = Synthesize(tone, kSamples, 0.0);
    for (int n = 0; n < kSamples; ++n) {
      const double t = n / kRateHz;
      if (decay_s > 0.0)
        samples(n, c) += amplitude * std::exp(-t / decay_s) * std::sin(2.0 * std::numbers::pi * kNaturalHz * t + c);
      samples(n, c) += noise_rel * amplitude * normal(rng);
    }
  }
  return samples;
}

// Phasors of the whole record and of its part from first_sample on.
void ExpectSamePhasors(const Eigen::MatrixXd& samples, Eigen::Index steady_start, double tolerance_in_std,
                       double tolerance_rel) {
  const Campaign campaign = SyntheticCampaign(kSensors, 47.25);
  const StepPhasors whole =
      EstimateStepPhasors(SyntheticRecording(campaign, samples, kRateHz), campaign, campaign.steps[0]);
  const StepPhasors steady = EstimateStepPhasors(
      SyntheticRecording(campaign, samples.bottomRows(kSamples - steady_start), kRateHz), campaign, campaign.steps[0]);
  EXPECT_EQ(steady.quality.settled_after_s, 0.0) << steady.quality.settling;
  EXPECT_GT(whole.quality.settled_after_s, 0.1) << whole.quality.settling;
  EXPECT_LT(whole.quality.settled_after_s, 0.3) << whole.quality.settling;
  EXPECT_NE(whole.quality.settling.find("transient dropped"), std::string::npos);
  for (const auto& name : {"force", "acc1", "acc2", "acc3"}) {
    const ChannelPhasors& a = *whole.Find(name);
    const ChannelPhasors& b = *steady.Find(name);
    for (int k = 1; k <= 5; ++k) {
      const HarmonicPhasor& ha = a.Harmonic(k);
      const HarmonicPhasor& hb = b.Harmonic(k);
      const double std = std::hypot(hb.std_real, hb.std_imag);
      EXPECT_LE(std::abs(ha.value - hb.value), tolerance_in_std * std + tolerance_rel * b.Harmonic(1).Amplitude())
          << name << " k=" << k << " whole " << ha.value << " steady " << hb.value << " std " << std;
    }
  }
}

TEST(SteadyStateTest, NoiseFreeTransientIsDropped) {
  // Decays to 1e-10 of the steady amplitude over the first 20 %.
  ExpectSamePhasors(Record(0.2 / std::log(1e10), 0.0, 1), kSamples / 5, 0.0, 1e-7);
}

TEST(SteadyStateTest, NoisyTransientIsDropped) {
  // Noise 1e-3 of the amplitude; the transient falls below a tenth of it at 20 %.
  const Eigen::MatrixXd samples = Record(0.2 / std::log(1e4), 1e-3, 2);
  ExpectSamePhasors(samples, kSamples / 5, 1.0, 0.0);

  // Without the detection the transient would bias the fit by many σ: the
  // test can tell.
  const Campaign campaign = SyntheticCampaign(kSensors, 47.25);
  PhasorEstimatorOptions keep_all;
  keep_all.steady_state.threshold = 1e12;  // everything counts as quiet
  const StepPhasors naive =
      EstimateStepPhasors(SyntheticRecording(campaign, samples, kRateHz), campaign, campaign.steps[0], keep_all);
  const StepPhasors steady = EstimateStepPhasors(SyntheticRecording(campaign, samples.bottomRows(4096), kRateHz),
                                                 campaign, campaign.steps[0]);
  EXPECT_EQ(naive.quality.settled_after_s, 0.0);
  double worst = 0.0;
  for (const auto& name : {"acc1", "acc2", "acc3"}) {
    const HarmonicPhasor& h = steady.Find(name)->Harmonic(1);
    worst = std::max(worst, std::abs(naive.Find(name)->Harmonic(1).value - h.value) / std::hypot(h.std_real, h.std_imag));
  }
  EXPECT_GT(worst, 5.0);
}

TEST(SteadyStateTest, SteadyNoisyRecordsKeepEverySample) {
  const std::vector<std::string> names{"force", "acc1", "acc2", "acc3"};
  for (unsigned seed = 10; seed < 20; ++seed) {
    const SteadyState state = DetectSteadyState(Record(0.0, 1e-2, seed), names, kRateHz, kFrequencyHz, 5, "x.csv");
    EXPECT_EQ(state.first_sample, 0) << "seed " << seed << ": " << state.reason;
    EXPECT_EQ(state.reason, "no transient detected");
  }
}

// Short records (10.5 periods in 256 samples: blocks shorter than 32 samples)
// still work and keep every sample when steady.
TEST(SteadyStateTest, ShortSteadyRecord) {
  std::mt19937 rng(12);
  Tone tone = RandomTone(rng, 5, 210.0);
  tone.sample_rate_hz = kRateHz;
  Eigen::MatrixXd samples(256, 2);
  samples.col(0) = Synthesize(tone, 256);
  samples.col(1) = 3.0 * samples.col(0);
  std::normal_distribution<double> normal;
  for (int n = 0; n < 256; ++n) samples(n, 1) += 1e-3 * normal(rng);
  const std::vector<std::string> names{"force", "acc1"};
  const SteadyState state = DetectSteadyState(samples, names, kRateHz, 210.0, 5, "short.csv");
  EXPECT_EQ(state.first_sample, 0) << state.reason;
}

TEST(SteadyStateTest, RecordThatNeverSettlesIsRejected) {
  const std::vector<std::string> names{"force", "acc1", "acc2", "acc3"};
  try {
    DetectSteadyState(Record(0.5, 1e-3, 3), names, kRateHz, kFrequencyHz, 5, "dir/step_007.csv");
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "dir/step_007.csv");
    EXPECT_FALSE(e.channel().empty());
    EXPECT_NE(std::string(e.what()).find("no steady state"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("Fix: record longer"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace beamid::signal
