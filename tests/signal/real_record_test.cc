// Records as real rigs make them, built here from the phasor convention
// (tests/signal/synthetic_signal.h), independent of the estimator:
//  - a response whose amplitude creeps 2 % over a 20 s record (a warming
//    support) is a steady state with drift: all of it is used, the result
//    says so, and the phasor is the record's mean within 3σ;
//  - a sensor's low-frequency wander (1/f², 30 % of the response) or 1/f
//    noise 20× the white noise is not taken for a transient;
//  - a shaker that stops at 80 % of the record: the ring-down is cut, said,
//    and the phasors are the driven ones within 3σ;
//  - a real slow transient near the drive frequency is still dropped: the
//    drift model does not swallow it.
#include <cmath>
#include <complex>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "hb/fftw_real_transform.h"
#include "signal/driven_span.h"
#include "signal/phasor_estimator.h"
#include "signal/steady_state.h"
#include "tests/signal/synthetic_signal.h"

namespace beamid::signal {
namespace {

using testing::Synthesize;
using testing::SyntheticCampaign;
using testing::SyntheticRecording;
using testing::Tone;

constexpr double kRateHz = 2048.0;
constexpr double kDuration_s = 20.0;
constexpr int kSamples = static_cast<int>(kRateHz * kDuration_s);
constexpr double kFrequencyHz = 31.7;
constexpr double kNoiseRel = 1e-3;
const std::complex<double> kForce{1.0, 0.0};
const std::complex<double> kResponse = std::polar(3.0, -1.1);

double Time_s(int n) { return n / kRateHz; }

// force and acc1: steady tones plus white noise.
Eigen::MatrixXd SteadyRecord(unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> normal;
  Eigen::MatrixXd samples(kSamples, 2);
  for (int c = 0; c < 2; ++c) {
    Tone tone;
    tone.frequency_hz = kFrequencyHz;
    tone.sample_rate_hz = kRateHz;
    tone.phasors = {c == 0 ? kForce : kResponse};
    samples.col(c) = Synthesize(tone, kSamples, 0.0);
    for (int n = 0; n < kSamples; ++n) samples(n, c) += kNoiseRel * std::abs(tone.phasors[0]) * normal(rng);
  }
  return samples;
}

// Coloured noise of the given RMS, power ∝ 1/f^exponent from 1/T to 100 Hz
// (three times the drive), random phases: the inverse DFT of that spectrum.
Eigen::VectorXd ColouredNoise(double rms, double exponent, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> phase(0.0, 2.0 * std::numbers::pi);
  hb::FftwRealTransform transform(kSamples);
  std::vector<std::complex<double>> bins(static_cast<std::size_t>(transform.num_bins()));
  for (int j = 1; j <= static_cast<int>(100.0 * kDuration_s); ++j)
    bins[static_cast<std::size_t>(j)] = std::polar(std::pow(j / kDuration_s, -0.5 * exponent), phase(rng));
  Eigen::VectorXd x(kSamples);
  transform.Inverse(bins.data(), x.data());
  return x * (rms / std::sqrt(x.squaredNorm() / kSamples));
}

StepPhasors Estimate(const Eigen::MatrixXd& samples) {
  const Campaign campaign = SyntheticCampaign(1, kFrequencyHz);
  return EstimateStepPhasors(SyntheticRecording(campaign, samples, kRateHz), campaign, campaign.steps[0]);
}

// The response fundamental against the truth, in standard uncertainties.
double ErrorInStd(const StepPhasors& step) {
  const HarmonicPhasor& h = step.responses[0].Harmonic(1);
  const std::complex<double> truth = kResponse * std::conj(kForce) / std::abs(kForce);
  const Eigen::Vector2d error(h.value.real() - truth.real(), h.value.imag() - truth.imag());
  return std::sqrt(error.dot(h.Covariance().inverse() * error) / 2.0);
}

bool Mentions(const std::vector<std::string>& lines, const std::string& text) {
  for (const auto& line : lines)
    if (line.find(text) != std::string::npos) return true;
  return false;
}

TEST(RealRecordTest, AmplitudeCreepIsASteadyStateWithDrift) {
  Eigen::MatrixXd samples = SteadyRecord(1);
  for (int n = 0; n < kSamples; ++n) samples(n, 1) *= 1.0 + 0.02 * (Time_s(n) / kDuration_s - 0.5);
  const StepPhasors step = Estimate(samples);
  EXPECT_EQ(step.quality.settled_after_s, 0.0) << step.quality.settling;
  EXPECT_NEAR(step.quality.analysed_duration_s, kDuration_s, 1e-9);
  EXPECT_TRUE(Mentions(step.quality.notes, "steady with drift")) << step.quality.settling;
  EXPECT_TRUE(Mentions(step.quality.notes, "changes by 2 %")) << step.quality.settling;
  EXPECT_LT(ErrorInStd(step), 3.0);
}

TEST(RealRecordTest, AmplitudeCreepWithoutTheDriftModelIsNoSteadyState) {
  // The reason for step 5: the periodic model alone keeps less than half.
  Eigen::MatrixXd samples = SteadyRecord(1);
  for (int n = 0; n < kSamples; ++n) samples(n, 1) *= 1.0 + 0.02 * (Time_s(n) / kDuration_s - 0.5);
  SteadyStateOptions periodic_only;
  periodic_only.drift_model = false;
  const std::vector<std::string> names{"force", "acc1"};
  try {
    const SteadyState state = DetectSteadyState(samples, names, kRateHz, kFrequencyHz, 5, "creep.csv", periodic_only);
    EXPECT_GT(state.first_sample, kSamples / 2) << state.reason;
  } catch (const std::invalid_argument&) {
    // "no steady state": what the periodic model alone said of such records.
  }
}

TEST(RealRecordTest, LowFrequencyNoiseIsNotATransient) {
  // A sensor's slow wander (power ∝ 1/f², 30 % of the response's amplitude)
  // and 1/f noise 20× the white noise, 10 realisations each: without the
  // wander removed from the residual, some of them lost 2–4 s.
  for (unsigned seed = 0; seed < 20; ++seed) {
    Eigen::MatrixXd samples = SteadyRecord(2 + seed);
    const bool wander = seed % 2 == 0;
    samples.col(1) += ColouredNoise((wander ? 0.3 : 0.02) * std::abs(kResponse), wander ? 2.0 : 1.0, 100 + seed);
    const StepPhasors step = Estimate(samples);
    EXPECT_LT(step.quality.settled_after_s, 0.05 * kDuration_s) << seed << ": " << step.quality.settling;
    EXPECT_LT(ErrorInStd(step), 3.0) << seed;
  }
}

TEST(RealRecordTest, ExcitationStoppingInsideTheRecordIsCutAndSaid) {
  Eigen::MatrixXd samples = SteadyRecord(4);
  const int stop = static_cast<int>(0.8 * kSamples);
  const double natural_hz = 33.1;
  std::mt19937 rng(5);
  std::normal_distribution<double> normal;
  const double phase_at_stop = std::arg(kResponse) + 2.0 * std::numbers::pi * kFrequencyHz * Time_s(stop);
  for (int n = stop; n < kSamples; ++n) {
    const double t = Time_s(n) - Time_s(stop);
    samples(n, 0) = kNoiseRel * normal(rng);
    samples(n, 1) = std::abs(kResponse) * std::exp(-t / 0.5) *
                        std::cos(2.0 * std::numbers::pi * natural_hz * t + phase_at_stop) +
                    kNoiseRel * std::abs(kResponse) * normal(rng);
  }
  const DrivenSpan span = FindDrivenSpan(samples.col(0), kRateHz, kFrequencyHz);
  EXPECT_TRUE(span.stops_early);
  EXPECT_FALSE(span.starts_late);
  EXPECT_LE(span.end_sample, stop);
  EXPECT_GT(span.end_sample, stop - 3 * static_cast<int>(kRateHz / kFrequencyHz));

  const StepPhasors step = Estimate(samples);
  EXPECT_TRUE(Mentions(step.quality.warnings, "stops before the end of the record")) << step.quality.settling;
  EXPECT_LE(step.quality.analysed_duration_s, 0.8 * kDuration_s);
  EXPECT_GT(step.quality.snr_db, 50.0);
  EXPECT_LT(ErrorInStd(step), 3.0);
  // A whole driven record is not cut.
  EXPECT_FALSE(FindDrivenSpan(SteadyRecord(6).col(0), kRateHz, kFrequencyHz).stops_early);
}

TEST(RealRecordTest, ASlowTransientNearTheDriveIsStillDropped) {
  Eigen::MatrixXd samples = SteadyRecord(7);
  const double natural_hz = kFrequencyHz * 1.02;
  for (int n = 0; n < kSamples; ++n)
    samples(n, 1) += std::abs(kResponse) * std::exp(-Time_s(n) / (kDuration_s / 8.0)) *
                     std::cos(2.0 * std::numbers::pi * natural_hz * Time_s(n));
  const StepPhasors step = Estimate(samples);
  // e^{-t/τ} falls to the 1e-3 noise after ~7τ: well past a third of the record.
  EXPECT_GT(step.quality.settled_after_s, 0.3 * kDuration_s) << step.quality.settling;
  EXPECT_FALSE(Mentions(step.quality.notes, "drift")) << step.quality.settling;
  EXPECT_LT(ErrorInStd(step), 3.0);
}

}  // namespace
}  // namespace beamid::signal
