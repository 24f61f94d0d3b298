// The half-power estimate of the measured backbone
// (solver/backbone/measured_backbone.h) on the closed-form receptance of one
// linear mode, H = 1/(ω_n² − ω² + 2iζω_nω) (unit modal mass), with seeded
// noise of the stated σ: on unevenly spaced steps, and on only seven, ζ, the
// natural frequency, the peak and both half-power frequencies lie within 3σ
// of their closed-form values
//   ω_p² = ω_n²(1 − 2ζ²), |H|_p = 1/(2ζω_n²√(1 − ζ²)),
//   ω_{1,2}² = ω_p² ∓ 2ζω_n²√(1 − ζ²);
// a curve that does not fall to 1/√2 on one side, or whose largest step is
// the sweep's last, gives no half-power number but a note (and, at the edge,
// the peak_outside_band flag).
#include <cmath>
#include <complex>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "solver/backbone/measured_backbone.h"

namespace beamid::solver {
namespace {

using ::testing::HasSubstr;

constexpr double kFn_hz = 40.0;
constexpr double kZeta = 0.02;
constexpr double kRelativeStd = 2e-3;

std::complex<double> Receptance(double f_hz) {
  const double wn = 2 * std::numbers::pi * kFn_hz, w = 2 * std::numbers::pi * f_hz;
  return 1.0 / std::complex<double>(wn * wn - w * w, 2 * kZeta * wn * w);
}

// A force-controlled displacement level at f_n·(1 + ζ·x) for each x of `offsets`.
signal::FirstHarmonicLevel Level(const std::vector<double>& offsets, unsigned seed) {
  std::mt19937 random(seed);
  std::normal_distribution<double> normal;
  signal::FirstHarmonicLevel level{.label = "level", .source = "level.csv", .channel = "disp",
                                   .response_quantity = signal::Quantity::kDisplacement};
  for (double x : offsets) {
    const double f = kFn_hz * (1 + kZeta * x);
    signal::FirstHarmonicPoint p{.frequency_hz = f};
    p.force.value = 1.0;
    std::complex<double> response = Receptance(f);
    const double sigma = kRelativeStd * std::abs(response) / std::sqrt(2.0);
    response += sigma * std::complex<double>(normal(random), normal(random));
    p.response.value = response;
    p.response.std_real = p.response.std_imag = sigma;
    level.points.push_back(p);
  }
  return level;
}

void ExpectWithin(const Estimate& e, double truth, const std::string& what) {
  ASSERT_TRUE(e.valid) << what;
  EXPECT_GT(e.std, 0.0) << what;
  EXPECT_LE(std::abs(e.value - truth), 3 * e.std) << what << ": " << e.value << " ± " << e.std << ", truth " << truth;
  // And the σ is not so wide that anything passes.
  EXPECT_LT(e.std, 0.2 * std::abs(truth)) << what;
}

void ExpectClosedForm(const LevelResonance& l) {
  const double wn2 = std::pow(2 * std::numbers::pi * kFn_hz, 2), root = std::sqrt(1 - kZeta * kZeta);
  const double wp2 = wn2 * (1 - 2 * kZeta * kZeta);
  const auto hz = [](double w2) { return std::sqrt(w2) / (2 * std::numbers::pi); };
  EXPECT_EQ(l.half_power_note, "");
  ExpectWithin(l.half_power_damping_ratio, kZeta, "half-power ζ");
  ExpectWithin(l.half_power_natural_frequency_hz, kFn_hz, "half-power natural frequency");
  ExpectWithin(l.peak_frequency_hz, hz(wp2), "peak frequency");
  ExpectWithin(l.peak_receptance_m_N, 1 / (2 * kZeta * wn2 * root), "peak |X/F|");
  ExpectWithin(l.half_power_lower_frequency_hz, hz(wp2 - 2 * kZeta * wn2 * root), "lower half-power frequency");
  ExpectWithin(l.half_power_upper_frequency_hz, hz(wp2 + 2 * kZeta * wn2 * root), "upper half-power frequency");
}

TEST(MeasuredBackboneHalfPower, UnevenStepsGiveTheClosedFormWithinTheirSigma) {
  for (unsigned seed : {1u, 2u, 3u}) {
    SCOPED_TRACE(seed);
    std::mt19937 random(100 + seed);
    std::uniform_real_distribution<double> uniform(-4.0, 4.0);
    std::vector<double> offsets;
    for (int i = 0; i < 25; ++i) offsets.push_back(uniform(random));
    std::sort(offsets.begin(), offsets.end());
    ExpectClosedForm(AnalyseMeasuredBackbone({Level(offsets, seed)}).levels[0]);
  }
}

TEST(MeasuredBackboneHalfPower, SevenStepsAreEnough) {
  for (unsigned seed : {4u, 5u, 6u}) {
    SCOPED_TRACE(seed);
    ExpectClosedForm(AnalyseMeasuredBackbone({Level({-3.1, -1.4, -0.45, 0.15, 0.8, 1.7, 3.6}, seed)}).levels[0]);
  }
}

TEST(MeasuredBackboneHalfPower, NoCrossingOnOneSideGivesANoteNotANumber) {
  // Up to 0.6 half-bandwidths above f_n: |H| stays above 1/√2 of its peak there.
  const LevelResonance l = AnalyseMeasuredBackbone({Level({-4, -3, -2, -1.2, -0.6, -0.2, 0.2, 0.6}, 7)}).levels[0];
  EXPECT_FALSE(l.half_power_damping_ratio.valid);
  EXPECT_FALSE(l.half_power_upper_frequency_hz.valid);
  EXPECT_FALSE(l.half_power_natural_frequency_hz.valid);
  EXPECT_TRUE(l.half_power_lower_frequency_hz.valid);
  EXPECT_THAT(l.half_power_note, HasSubstr("above the peak"));
}

TEST(MeasuredBackboneHalfPower, APeakAtTheLastStepIsFlaggedNotEstimated) {
  const LevelResonance l = AnalyseMeasuredBackbone({Level({-5, -4, -3, -2.5, -2, -1.5}, 8)}).levels[0];
  EXPECT_FALSE(l.half_power_damping_ratio.valid);
  EXPECT_FALSE(l.peak_frequency_hz.valid);
  EXPECT_THAT(l.half_power_note, HasSubstr("end of the sweep"));
  EXPECT_TRUE(l.HasFlag(LevelFlagKind::kPeakOutsideBand));
}

}  // namespace
}  // namespace beamid::solver
