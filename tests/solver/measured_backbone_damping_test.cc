// The damping the measured backbone (solver/backbone/measured_backbone.h)
// reports, on closed-form single-mode levels:
//  - the level's ζ and its σ: where the three estimators (phase resonance,
//    local fit, half-power) disagree beyond their noise — a second mode close
//    by — the stated σ covers every one of them and a note says which to
//    trust; where they agree the σ stays that of the noise;
//  - the damping trend against amplitude, judged against a constant damper
//    (ζω_n constant): response-controlled levels (|X_d| held, so each level
//    is the linear FRF of ω_n(a), ζω_n(a): X_d/F = 1/(ω_n²(a) − ω² +
//    2iω·ζω_n(a))) of a softening mode with a constant damper give a ζ that
//    rises (the frequency falls) but no "rises beyond a constant damper";
//    the same mode with ζω_n growing with amplitude does get it.
#include <algorithm>
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

constexpr double kRelativeStd = 2e-3;
constexpr double kTwoPi = 2 * std::numbers::pi;

// ---------------------------------------------------------------- ζ's σ

// A force-controlled displacement level (1 N) of one mode at 50 Hz, ζ 1 %,
// plus (second_hz > 0) a second mode of the same modal mass and damping.
signal::FirstHarmonicLevel TwoModeLevel(const std::string& label, double second_hz, unsigned seed) {
  std::mt19937 random(seed);
  std::normal_distribution<double> normal;
  signal::FirstHarmonicLevel level{.label = label, .source = label + ".csv", .channel = "disp",
                                   .response_quantity = signal::Quantity::kDisplacement};
  auto mode = [](double fn, double f) {
    const double wn = kTwoPi * fn, w = kTwoPi * f;
    return 1.0 / std::complex<double>(wn * wn - w * w, 2 * 0.01 * wn * w);
  };
  for (double f = 47.0; f <= 53.0 + 1e-9; f += 0.1) {
    std::complex<double> x = mode(50.0, f) + (second_hz > 0 ? mode(second_hz, f) : 0.0);
    const double sigma = kRelativeStd * std::abs(x) / std::sqrt(2.0);
    x += sigma * std::complex<double>(normal(random), normal(random));
    signal::FirstHarmonicPoint p{.frequency_hz = f};
    p.force.value = 1.0;
    p.response.value = x;
    p.response.std_real = p.response.std_imag = sigma;
    level.points.push_back(p);
  }
  return level;
}

std::vector<const Estimate*> Estimators(const LevelResonance& l) {
  std::vector<const Estimate*> out;
  for (const Estimate* e : {&l.quadrature_damping_ratio, &l.local_damping_ratio, &l.half_power_damping_ratio})
    if (e->valid) out.push_back(e);
  return out;
}

TEST(MeasuredBackboneDamping, TheStatedSigmaCoversEstimatorsThatDisagree) {
  const MeasuredBackbone result = AnalyseMeasuredBackbone({TwoModeLevel("two modes", 51.5, 1)});
  const LevelResonance& l = result.levels[0];
  const auto estimators = Estimators(l);
  ASSERT_GE(estimators.size(), 2u);
  // The case: at least two estimators part by more than their own noise.
  double worst = 0.0;
  for (const Estimate* a : estimators)
    for (const Estimate* b : estimators) worst = std::max(worst, std::abs(a->value - b->value) / std::hypot(a->std, b->std));
  ASSERT_GT(worst, 3.0) << "the estimators must disagree for this test";
  ASSERT_TRUE(l.damping_ratio.valid);
  for (const Estimate* e : estimators)
    EXPECT_LE(std::abs(e->value - l.damping_ratio.value), l.damping_ratio.std)
        << e->value << " against " << l.damping_ratio.value << " ± " << l.damping_ratio.std;
  EXPECT_THAT(l.damping_ratio_note, HasSubstr("part by more than their noise"));
  EXPECT_THAT(l.damping_ratio_note, HasSubstr("Trust the phase resonance"));
}

TEST(MeasuredBackboneDamping, AgreeingEstimatorsKeepTheSigmaOfTheNoise) {
  const LevelResonance l = AnalyseMeasuredBackbone({TwoModeLevel("one mode", 0.0, 2)}).levels[0];
  ASSERT_TRUE(l.damping_ratio.valid);
  EXPECT_EQ(l.damping_ratio_note, "");
  EXPECT_LE(std::abs(l.damping_ratio.value - 0.01), 3 * l.damping_ratio.std);
  EXPECT_LT(l.damping_ratio.std, 3 * l.quadrature_damping_ratio.std);
  for (const Estimate* e : Estimators(l)) EXPECT_LE(std::abs(e->value - l.damping_ratio.value), l.damping_ratio.std);
}

// ---------------------------------------------------------------- the trend

constexpr double kF0_hz = 50.0;
constexpr double kReference_m = 1e-3;

struct Mode {
  double softening = 0.0;     // ω_n²(a) = ω0²·(1 − softening·s²), s = a/a_ref
  double rate_growth = 0.0;   // ζω_n(a) = ζ0·ω0·(1 + rate_growth·s)
  double zeta0 = 0.01;
  double OmegaSquared(double a) const {
    return std::pow(kTwoPi * kF0_hz, 2) * (1 - softening * std::pow(a / kReference_m, 2));
  }
  double Rate(double a) const { return zeta0 * kTwoPi * kF0_hz * (1 + rate_growth * a / kReference_m); }
};

// A response-controlled level: |X_d| = a at every step, F = D·X_d (A = 1).
signal::FirstHarmonicLevel HeldLevel(const Mode& mode, double a, unsigned seed) {
  std::mt19937 random(seed);
  std::normal_distribution<double> normal;
  signal::FirstHarmonicLevel level{.label = std::to_string(a), .source = "held.csv", .channel = "disp",
                                   .response_quantity = signal::Quantity::kDisplacement};
  const double fn = std::sqrt(mode.OmegaSquared(a)) / kTwoPi, half_band = mode.Rate(a) / kTwoPi;
  for (int k = -20; k <= 20; ++k) {
    const double f = fn + 0.2 * half_band * k, w = kTwoPi * f;
    const std::complex<double> d(mode.OmegaSquared(a) - w * w, 2 * w * mode.Rate(a));
    signal::FirstHarmonicPoint p{.frequency_hz = f};
    p.force.value = std::abs(d) * a;                       // the force's phase is the reference
    std::complex<double> x = a * std::conj(d) / std::abs(d);  // X_d = F/D
    const double sigma = kRelativeStd * a / std::sqrt(2.0);
    x += sigma * std::complex<double>(normal(random), normal(random));
    p.response.value = x;
    p.response.std_real = p.response.std_imag = sigma;
    level.points.push_back(p);
  }
  return level;
}

MeasuredBackbone Campaign(const Mode& mode) {
  std::vector<signal::FirstHarmonicLevel> levels;
  unsigned seed = 10;
  for (double s : {0.2, 0.4, 0.6, 0.8, 1.0}) levels.push_back(HeldLevel(mode, s * kReference_m, seed++));
  return AnalyseMeasuredBackbone(levels);
}

TEST(MeasuredBackboneDamping, AConstantDamperOnASofteningSupportIsNotDampingThatRises) {
  // ω_n falls by 10 % across the levels, so ζ = ζω_n/ω_n rises by 11 %.
  const MeasuredBackbone result = Campaign({.softening = 0.2});
  ASSERT_TRUE(result.fit.ok);
  const DampingTrend& t = result.damping_trend;
  EXPECT_EQ(t.damping_ratio_verdict, Trend::kRises) << "z = " << t.z;  // what was reported before
  EXPECT_GT(t.z, 3.0);
  EXPECT_EQ(t.verdict, Trend::kNone) << "damping-rate z = " << t.damping_rate_z;
  EXPECT_LT(std::abs(t.damping_rate_z), 3.0);
}

TEST(MeasuredBackboneDamping, ADampingRateGrowingWithAmplitudeRisesBeyondAConstantDamper) {
  const MeasuredBackbone result = Campaign({.softening = 0.2, .rate_growth = 0.3});
  ASSERT_TRUE(result.fit.ok);
  const DampingTrend& t = result.damping_trend;
  EXPECT_EQ(t.verdict, Trend::kRises) << "damping-rate z = " << t.damping_rate_z;
  EXPECT_GT(t.damping_rate_z, 3.0);
  // ζω_n = ζ0·ω0·(1 + 0.3·s): its slope 0.3·ζ0·ω0/a_ref, within 3σ.
  const double truth = 0.3 * 0.01 * kTwoPi * kF0_hz / kReference_m;
  EXPECT_LE(std::abs(t.damping_rate_slope_per_s_m - truth), 3 * t.damping_rate_slope_std_per_s_m)
      << t.damping_rate_slope_per_s_m << " ± " << t.damping_rate_slope_std_per_s_m << ", truth " << truth;
}

}  // namespace
}  // namespace beamid::solver
