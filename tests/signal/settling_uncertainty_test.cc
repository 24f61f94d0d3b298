// The uncertainty of a record cut before it settled (signal/settling_uncertainty.h),
// on synthetic records whose steady phasors are known: a steady
// multi-harmonic response plus, in one channel, a free vibration decaying at
// a nearby natural frequency. The raised covariance must make the phasors'
// actual error (estimate − the synthesis's steady phasor) a plausible draw,
// where the noise-only covariance misses it by orders of magnitude; a record
// with noise only must raise nothing beyond the test's false-alarm rate
// (χ²(2) ≥ 13.8 ⇔ p = 0.001); and the whole chain (EstimateStepPhasors) must
// flag such a record, say so, and weigh it less than the same record settled.
#include "signal/settling_uncertainty.h"

#include <cmath>
#include <complex>
#include <cstdio>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include <Eigen/LU>
#include <gtest/gtest.h>

#include "signal/harmonic_fit.h"
#include "signal/phasor_estimator.h"
#include "tests/signal/synthetic_signal.h"

namespace beamid::signal {
namespace {

using Complex = std::complex<double>;
using testing::Synthesize;
using testing::SyntheticCampaign;
using testing::SyntheticRecording;
using testing::Tone;

constexpr double kRateHz = 5120.0;
constexpr double kFrequencyHz = 54.0;
constexpr int kHarmonics = 5;

// A free vibration A·e^{−t/T}·cos(2π f_n t + φ), t from the first sample.
struct FreeVibration {
  double amplitude = 0.0;
  double time_constant_s = 1.0;
  double frequency_hz = 55.5;
  double phase_rad = 0.0;
  double At(int n) const {
    const double t = n / kRateHz;
    return amplitude * std::exp(-t / time_constant_s) *
           std::cos(2.0 * std::numbers::pi * frequency_hz * t + phase_rad);
  }
};

// Force, acc1 and acc2: steady tones (time origin at sample 0) plus white
// noise of the given rms per channel; acc1 also holds `transient`.
struct Record {
  std::vector<Tone> tones;  // force first
  Eigen::MatrixXd steady;   // without noise and transient
  Eigen::MatrixXd samples;
};

Record MakeRecord(unsigned seed, int num_samples, const FreeVibration& transient, double noise_rms_relative) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> normal;
  Record record;
  // Fixed tones (not drawn from the seed): every seed is a noise draw of one record.
  const std::vector<std::vector<Complex>> phasors{
      {std::polar(2.0, 0.4), std::polar(0.02, 1.0), std::polar(0.006, -2.0), std::polar(0.002, 0.5), std::polar(0.001, 2.5)},
      {std::polar(10.0, -1.1), std::polar(0.5, 0.7), std::polar(0.3, 2.9), std::polar(0.05, -0.4), std::polar(0.02, 1.3)},
      {std::polar(6.0, 0.9), std::polar(0.2, -2.2), std::polar(0.1, 0.1), std::polar(0.03, 1.9), std::polar(0.01, -1.0)}};
  record.steady.resize(num_samples, 3);
  record.samples.resize(num_samples, 3);
  for (int c = 0; c < 3; ++c) {
    Tone tone{.frequency_hz = kFrequencyHz, .sample_rate_hz = kRateHz, .mean = 0.1 * c, .phasors = phasors[c]};
    record.steady.col(c) = Synthesize(tone, num_samples, 0.0);
    const double sigma = noise_rms_relative * std::abs(tone.phasors[0]);
    for (int n = 0; n < num_samples; ++n)
      record.samples(n, c) = record.steady(n, c) + sigma * normal(rng) + (c == 1 ? transient.At(n) : 0.0);
    record.tones.push_back(tone);
  }
  return record;
}

// The synthesis's steady phasor of channel c, harmonic k, referenced to the
// force fundamental (phasor_set.h): Z_k = X_k·e^{−ik·arg F_1}.
Complex SteadyTruth(const Record& record, int c, int k) {
  const double phi = std::arg(record.tones[0].phasors[0]);
  return record.tones[static_cast<std::size_t>(c)].phasors[static_cast<std::size_t>(k - 1)] * std::polar(1.0, -k * phi);
}

// The transient's phasor at harmonic k over samples [begin, end), referenced
// like SteadyTruth: its projection (2/N)·Σ x_n e^{−ikωt_n}. Exact for the
// least-squares fit when the segment holds a whole number of periods (the
// basis is then orthogonal), which the tests below arrange.
Complex TransientPhasor(const FreeVibration& transient, int begin, int end, int k, double force_phase_rad) {
  Complex sum = 0.0;
  const double omega = 2.0 * std::numbers::pi * kFrequencyHz;
  for (int n = begin; n < end; ++n) sum += transient.At(n) * std::polar(1.0, -k * omega * n / kRateHz);
  return 2.0 / (end - begin) * sum * std::polar(1.0, -k * force_phase_rad);
}

double Quadratic(const Eigen::Matrix2d& covariance, Complex error) {
  const Eigen::Vector2d e(error.real(), error.imag());
  return e.dot(covariance.inverse() * e);
}

std::vector<ChannelPhasors> Phasors(const Eigen::MatrixXd& samples, const std::vector<const ChannelSpec*>& specs) {
  return ReferencePhasors(FitHarmonics(samples, kRateHz, kFrequencyHz, kHarmonics), 0, specs);
}

TEST(SettlingUncertaintyTest, RaisedCovarianceCoversTheErrorThatTheNoiseCovarianceMisses) {
  const Campaign campaign = SyntheticCampaign(2, kFrequencyHz);
  const auto specs = campaign.Channels();
  // One second, 54 whole periods; each half 27. The free vibration, half a
  // frequency bin from the drive (so that little of it leaks into the noise
  // floor the fit reads beside the harmonics), starts at 30 % of acc1's
  // fundamental and is still 4 % of it at the end.
  const int n = 5120;
  const FreeVibration transient{.amplitude = 3.0, .time_constant_s = 0.5, .frequency_hz = 54.5, .phase_rad = 0.8};
  const Record record = MakeRecord(11, n, transient, 1e-3);
  const std::vector<ChannelPhasors> noise_only = Phasors(record.samples, specs);
  std::vector<ChannelPhasors> raised = noise_only;
  const SettlingUncertainty result =
      AddSettlingUncertainty(record.samples, kRateHz, kFrequencyHz, kHarmonics, specs, {true, true, true}, raised);

  ASSERT_TRUE(result.raised);
  EXPECT_EQ(result.channel, "acc1");

  // acc1's fundamental: its error is the transient's share of the whole
  // part; the noise covariance misses it by orders of magnitude, the raised
  // one holds it.
  const double phi = std::arg(record.tones[0].phasors[0]);
  const Complex error = noise_only[1].Harmonic(1).value - SteadyTruth(record, 1, 1);
  // The error is what the synthesis says it is (the check of this test's own algebra).
  const double noise_std = 1e-3 * 10.0 * std::sqrt(2.0 / n);  // σ·√(2/N) per component
  EXPECT_LT(std::abs(error - TransientPhasor(transient, 0, n, 1, phi)), 6.0 * noise_std);
  const Eigen::Matrix2d before = noise_only[1].Harmonic(1).Covariance();
  const Eigen::Matrix2d after = raised[1].Harmonic(1).Covariance();
  std::printf("acc1 h1: |error| %.4g, chi2 under the noise covariance %.4g, under the raised one %.4g\n",
              std::abs(error), Quadratic(before, error), Quadratic(after, error));
  EXPECT_GT(Quadratic(before, error), 1e4);
  EXPECT_LT(Quadratic(after, error), 20.0);
  EXPECT_LT(error.real() * error.real() / after(0, 0), 20.0);
  EXPECT_LT(error.imag() * error.imag() / after(1, 1), 20.0);

  // Every phasor of every channel (the force's fundamental excepted: real by
  // construction) is consistent with its covariance after the raise; the
  // transient's leakage into acc1's higher harmonics too.
  int missed_before = 0;
  for (int c = 0; c < 3; ++c)
    for (int k = 1; k <= kHarmonics; ++k) {
      if (c == 0 && k == 1) continue;
      const Complex e = noise_only[c].Harmonic(k).value - SteadyTruth(record, c, k);
      const double chi2_before = Quadratic(noise_only[c].Harmonic(k).Covariance(), e);
      const double chi2_after = Quadratic(raised[c].Harmonic(k).Covariance(), e);
      if (chi2_before > 20.0) ++missed_before;
      EXPECT_LT(chi2_after, 20.0) << raised[c].channel << " h" << k << " (before the raise " << chi2_before << ")";
      // The channels without the transient keep their covariance.
      if (c != 1) {
        EXPECT_EQ(raised[c].Harmonic(k).Covariance(), noise_only[c].Harmonic(k).Covariance())
            << raised[c].channel << " h" << k;
      }
    }
  EXPECT_GE(missed_before, 1);

  // change_relative: |ΔX_1|/|X_1| between the halves, from the synthesis
  // (the steady part is the same in both halves, so ΔX is the transient's).
  const Complex change = TransientPhasor(transient, 0, n / 2, 1, phi) - TransientPhasor(transient, n / 2, n, 1, phi);
  const Complex whole = SteadyTruth(record, 1, 1) + TransientPhasor(transient, 0, n, 1, phi);
  const double expected = std::abs(change) / std::abs(whole);
  std::printf("change_relative %.5g, expected %.5g\n", result.change_relative, expected);
  EXPECT_NEAR(result.change_relative, expected, 0.01 * expected);
  // What the raise adds is |ΔX|²/2 per component.
  EXPECT_NEAR(after(0, 0) - before(0, 0), 0.5 * std::norm(change), 0.02 * 0.5 * std::norm(change));
  EXPECT_NEAR(after(1, 1) - before(1, 1), 0.5 * std::norm(change), 0.02 * 0.5 * std::norm(change));
  EXPECT_NEAR(after(0, 1), before(0, 1), 1e-12 * after(0, 0));
}

TEST(SettlingUncertaintyTest, OnlyTheUsedChannelsAreRaised) {
  const Campaign campaign = SyntheticCampaign(2, kFrequencyHz);
  const auto specs = campaign.Channels();
  const FreeVibration transient{.amplitude = 3.0, .time_constant_s = 0.5, .frequency_hz = 54.5, .phase_rad = 0.8};
  const Record record = MakeRecord(12, 5120, transient, 1e-3);
  const std::vector<ChannelPhasors> noise_only = Phasors(record.samples, specs);
  std::vector<ChannelPhasors> phasors = noise_only;
  const SettlingUncertainty result =
      AddSettlingUncertainty(record.samples, kRateHz, kFrequencyHz, kHarmonics, specs, {true, false, true}, phasors);
  EXPECT_FALSE(result.raised);
  EXPECT_EQ(result.change_relative, 0.0);
  EXPECT_EQ(result.channel, "");
  for (int k = 1; k <= kHarmonics; ++k)
    EXPECT_EQ(phasors[1].Harmonic(k).Covariance(), noise_only[1].Harmonic(k).Covariance()) << "h" << k;
}

TEST(SettlingUncertaintyTest, ASteadyRecordRaisesNothingBeyondTheFalseAlarmRate) {
  const Campaign campaign = SyntheticCampaign(2, kFrequencyHz);
  const auto specs = campaign.Channels();
  // 50 noise draws × 14 tested phasors (force h2..h5, acc1 and acc2 h1..h5).
  // On a steady record |ΔX_k|² against 4·Cov X_k is χ²(2): P(≥ x) = e^{−x/2}.
  // At the default 13.8 (p = 0.001) ~0.7 false alarms are expected; the
  // same statistic at the limits of p = 0.01 and p = 0.1 must raise ~7 and
  // ~70 (a test that forgot the factor 4 would raise ~125 at 13.8).
  constexpr int kDraws = 50;
  struct Level {
    double chi2;
    int raised_phasors = 0, raised_records = 0;
  };
  std::vector<Level> levels{{13.8}, {-2.0 * std::log(0.01)}, {-2.0 * std::log(0.1)}};
  int tested = 0;
  for (int seed = 1; seed <= kDraws; ++seed) {
    const Record record = MakeRecord(static_cast<unsigned>(100 + seed), 5120, {}, 1e-3);
    const std::vector<ChannelPhasors> before = Phasors(record.samples, specs);
    for (Level& level : levels) {
      std::vector<ChannelPhasors> after = before;
      const SettlingUncertainty result = AddSettlingUncertainty(record.samples, kRateHz, kFrequencyHz, kHarmonics,
                                                                specs, {true, true, true}, after, level.chi2);
      level.raised_records += result.raised ? 1 : 0;
      for (int c = 0; c < 3; ++c)
        for (int k = 1; k <= kHarmonics; ++k) {
          if (c == 0 && k == 1) continue;
          if (&level == &levels.front()) ++tested;
          if (after[c].Harmonic(k).Covariance() != before[c].Harmonic(k).Covariance()) ++level.raised_phasors;
        }
      if (!result.raised) {
        EXPECT_EQ(result.change_relative, 0.0);
        EXPECT_TRUE(result.channel.empty());
      }
    }
  }
  for (const Level& level : levels)
    std::printf("threshold %.2f: raised %d of %d phasors, in %d of %d records\n", level.chi2, level.raised_phasors,
                tested, level.raised_records, kDraws);
  EXPECT_EQ(tested, 14 * kDraws);
  // The default: nothing raised beyond the rate (Poisson(0.7): P(≥ 5) = 6e-4).
  EXPECT_LE(levels[0].raised_phasors, 4);
  EXPECT_LE(levels[0].raised_records, 4);
  // The statistic's calibration: 7 expected (P(outside 2..16) < 1 %), 70 expected (±3σ).
  EXPECT_GE(levels[1].raised_phasors, 2);
  EXPECT_LE(levels[1].raised_phasors, 16);
  EXPECT_GE(levels[2].raised_phasors, 45);
  EXPECT_LE(levels[2].raised_phasors, 95);
}

// Through the whole chain: a 3 s record whose free vibration (acc1, at
// 55 Hz, from 50 % of the response) decays over most of it. The steady-state
// detection keeps the part where the transient is below the noise of one
// period's block, but coherent over the many periods left it still moves the
// phasors.
TEST(SettlingUncertaintyTest, EstimateStepPhasorsFlagsARecordCutBeforeItSettled) {
  const Campaign campaign = SyntheticCampaign(2, kFrequencyHz);
  const int n = 3 * 5120;
  const FreeVibration transient{.amplitude = 5.0, .time_constant_s = 0.3, .frequency_hz = 55.0, .phase_rad = 0.3};
  const Record unsettled_record = MakeRecord(21, n, transient, 1e-3);
  const Record settled_record = MakeRecord(21, n, {}, 1e-3);  // the same noise, no transient
  const StepPhasors unsettled =
      EstimateStepPhasors(SyntheticRecording(campaign, unsettled_record.samples, kRateHz), campaign, campaign.steps[0]);
  const StepPhasors settled =
      EstimateStepPhasors(SyntheticRecording(campaign, settled_record.samples, kRateHz), campaign, campaign.steps[0]);
  std::printf("settled after %.3g s (%s)\n", unsettled.quality.settled_after_s, unsettled.quality.settling.c_str());
  for (const auto& w : unsettled.quality.warnings) std::printf("warning: %s\n", w.c_str());

  EXPECT_FALSE(settled.quality.unsettled);
  EXPECT_TRUE(settled.quality.warnings.empty());
  ASSERT_TRUE(unsettled.quality.unsettled);
  EXPECT_EQ(unsettled.quality.unsettled_channel, "acc1");
  EXPECT_GT(unsettled.quality.unsettled_change_relative, 0.0);
  // More than half of the record was dropped, and the warning says what is left.
  EXPECT_GT(unsettled.quality.settled_after_s, 0.5 * n / kRateHz);
  bool warned = false;
  for (const auto& w : unsettled.quality.warnings)
    if (w.find("the transient took") != std::string::npos && w.find("changes 'acc1' by") != std::string::npos &&
        w.find("between the halves of the analysed part") != std::string::npos)
      warned = true;
  EXPECT_TRUE(warned);

  // The covariance of acc1's fundamental: larger than the settled record's,
  // also than the settled record's analysed over the same (shorter) part;
  // and it covers the actual error.
  const int analysed = static_cast<int>(std::lround(unsettled.quality.analysed_duration_s * kRateHz));
  const Record settled_tail{.tones = settled_record.tones, .steady = settled_record.steady.bottomRows(analysed),
                            .samples = settled_record.samples.bottomRows(analysed)};
  const StepPhasors settled_short =
      EstimateStepPhasors(SyntheticRecording(campaign, settled_tail.samples, kRateHz), campaign, campaign.steps[0]);
  const Eigen::Matrix2d raised = unsettled.responses[0].Harmonic(1).Covariance();
  const Eigen::Matrix2d full = settled.responses[0].Harmonic(1).Covariance();
  const Eigen::Matrix2d same_length = settled_short.responses[0].Harmonic(1).Covariance();
  std::printf("acc1 h1 variance trace: unsettled %.4g, settled %.4g, settled over the same length %.4g\n",
              raised.trace(), full.trace(), same_length.trace());
  EXPECT_GT(raised.trace(), 10.0 * same_length.trace());
  EXPECT_GT(raised.trace(), full.trace());
  const Complex error = unsettled.responses[0].Harmonic(1).value - SteadyTruth(unsettled_record, 1, 1);
  std::printf("acc1 h1 error chi2: %.3g (the same-length settled covariance would give %.3g)\n", Quadratic(raised, error),
              Quadratic(same_length, error));
  EXPECT_LT(Quadratic(raised, error), 20.0);
  EXPECT_GT(Quadratic(same_length, error), 20.0);
  // Without the raise (settling_uncertainty off) the same record keeps its
  // warning but not its weight: the noise covariance misses the error.
  PhasorEstimatorOptions unweighed;
  unweighed.settling_uncertainty = false;
  const StepPhasors plain =
      EstimateStepPhasors(SyntheticRecording(campaign, unsettled_record.samples, kRateHz), campaign, campaign.steps[0],
                          unweighed);
  EXPECT_FALSE(plain.quality.unsettled);
  EXPECT_EQ(plain.responses[0].Harmonic(1).value, unsettled.responses[0].Harmonic(1).value);
  EXPECT_GT(Quadratic(plain.responses[0].Harmonic(1).Covariance(), error), 20.0);
  // acc2 has no transient: its covariance is the settled record's of that length.
  const double acc2 = unsettled.responses[1].Harmonic(1).Covariance().trace();
  const double acc2_settled = settled_short.responses[1].Harmonic(1).Covariance().trace();
  EXPECT_LT(acc2, 1.5 * acc2_settled);
  EXPECT_GT(acc2, acc2_settled / 1.5);
}

}  // namespace
}  // namespace beamid::signal
