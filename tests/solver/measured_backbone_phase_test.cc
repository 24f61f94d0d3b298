// The phase-convention check of the measured backbone
// (solver/backbone/phase_convention.h): a closed-form single mode measured
// as an acceleration, A = −ω²·F/(ω_n² − ω² + 2iωζω_n) in beamid's convention
// x(t) = Re(X e^{iωt}), runs π → 0 through its resonance and is not flagged;
// the same table from a sensor mounted upside down (−A: 0 → −π, a
// displacement's course) and one written in the other convention (conj A:
// the phase rises) are flagged "phase_convention", with the course in the
// message, next to the phase in the summary's terms, and the level leaves
// the cross-level fit.
#include <cmath>
#include <complex>
#include <functional>
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

signal::FirstHarmonicLevel Acceleration(const std::string& label, double force_N,
                                        const std::function<std::complex<double>(std::complex<double>)>& mounting,
                                        unsigned seed) {
  std::mt19937 random(seed);
  std::normal_distribution<double> normal;
  signal::FirstHarmonicLevel level{.label = label, .source = label + ".csv", .channel = "acc",
                                   .response_quantity = signal::Quantity::kAcceleration};
  const double wn = 2 * std::numbers::pi * 30.0;
  for (double f = 28.0; f <= 32.0 + 1e-9; f += 0.05) {
    const double w = 2 * std::numbers::pi * f;
    std::complex<double> a = -w * w * force_N / std::complex<double>(wn * wn - w * w, 2 * 0.01 * wn * w);
    const double sigma = 2e-3 * std::abs(a) / std::sqrt(2.0);
    a += sigma * std::complex<double>(normal(random), normal(random));
    signal::FirstHarmonicPoint p{.frequency_hz = f};
    p.force.value = force_N;
    p.response.value = mounting(a);
    p.response.std_real = p.response.std_imag = sigma;
    level.points.push_back(p);
  }
  return level;
}

std::string Flags(const LevelResonance& l) {
  std::string text;
  for (const auto& f : l.flags) text += std::string(LevelFlagName(f.kind)) + ": " + f.message + "\n";
  return text;
}

const auto kAsMounted = [](std::complex<double> a) { return a; };
const auto kUpsideDown = [](std::complex<double> a) { return -a; };
const auto kOtherConvention = [](std::complex<double> a) { return std::conj(a); };

TEST(MeasuredBackbonePhase, AnAccelerationRunningFromPiToZeroIsNotFlagged) {
  const MeasuredBackbone result =
      AnalyseMeasuredBackbone({Acceleration("low", 1.0, kAsMounted, 1), Acceleration("high", 2.0, kAsMounted, 2)});
  for (const auto& l : result.levels) EXPECT_FALSE(l.HasFlag(LevelFlagKind::kPhaseConvention)) << Flags(l);
}

TEST(MeasuredBackbonePhase, ASensorMountedUpsideDownIsSaid) {
  const MeasuredBackbone result = AnalyseMeasuredBackbone(
      {Acceleration("low", 1.0, kAsMounted, 3), Acceleration("flipped", 1.5, kUpsideDown, 4),
       Acceleration("high", 2.0, kAsMounted, 5)});
  const LevelResonance& l = result.levels[1];
  ASSERT_TRUE(l.HasFlag(LevelFlagKind::kPhaseConvention)) << Flags(l);
  EXPECT_EQ(l.FlagNote("phase"), "[FLAG: phase convention]");
  EXPECT_THAT(Flags(l), HasSubstr("acceleration's phase runs"));
  EXPECT_THAT(Flags(l), HasSubstr("upside down"));
  EXPECT_FALSE(l.in_global_fit);
  EXPECT_FALSE(result.levels[0].HasFlag(LevelFlagKind::kPhaseConvention)) << Flags(result.levels[0]);
  EXPECT_TRUE(result.levels[0].in_global_fit);
}

TEST(MeasuredBackbonePhase, APhaseOfTheOtherConventionIsSaid) {
  const LevelResonance l = AnalyseMeasuredBackbone({Acceleration("conjugate", 1.0, kOtherConvention, 6)}).levels[0];
  ASSERT_TRUE(l.HasFlag(LevelFlagKind::kPhaseConvention)) << Flags(l);
  EXPECT_THAT(Flags(l), HasSubstr("rises through the resonance"));
  EXPECT_THAT(Flags(l), HasSubstr("negate the phase column"));
}

}  // namespace
}  // namespace beamid::solver
