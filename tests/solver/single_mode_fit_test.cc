// Known answers: a linear single-degree-of-freedom oscillator's exact
// receptance X/F = A/(ω_n² − ω² + 2iζω_nω) (closed form, not the model of
// the beam) must give back ω_n, ζ and A from the single-mode fit, and the
// measured-backbone analysis must find its phase resonance and damping by
// all three methods.
#include "solver/single_mode_fit.h"

#include <cmath>
#include <complex>
#include <numbers>

#include <gtest/gtest.h>

#include "signal/first_harmonic_level.h"
#include "solver/measured_backbone.h"

namespace beamid::solver {
namespace {

constexpr double kNaturalFrequency_hz = 54.0, kDampingRatio = 0.006, kModalConstant = 0.8;  // A [1/kg]
constexpr double kExact = 1e-9;          // relative, for exact-data fits
constexpr double kHalfPowerBias = 0.01;  // half-power's own approximation at ζ = 0.6 %

std::complex<double> Receptance(double omega) {
  const double wn = 2 * std::numbers::pi * kNaturalFrequency_hz;
  return kModalConstant / std::complex<double>(wn * wn - omega * omega, 2 * kDampingRatio * wn * omega);
}

signal::FirstHarmonicLevel SdofLevel(double force_N) {
  signal::FirstHarmonicLevel level{.label = "sdof", .source = "closed form",
                                   .response_quantity = signal::Quantity::kAcceleration};
  for (double f = 52.0; f <= 56.01; f += 0.2) {
    const double omega = 2 * std::numbers::pi * f;
    signal::FirstHarmonicPoint p{.frequency_hz = f};
    p.force.value = force_N;
    p.response.value = -omega * omega * Receptance(omega) * force_N;  // acceleration
    level.points.push_back(p);
  }
  return level;
}

TEST(SingleModeFit, RecoversALinearOscillatorExactly) {
  std::vector<SingleModePoint> points;
  for (double f = 53.0; f <= 55.0; f += 0.25) {
    const double omega = 2 * std::numbers::pi * f;
    const std::complex<double> x = Receptance(omega);
    points.push_back({.omega_rad_s = omega, .inverse_receptance_N_m = 1.0 / x, .amplitude_m = std::abs(x)});
  }
  const SingleModeFit fit = FitSingleMode(points, {.frequency_degree = 1, .damping_degree = 1, .reference_amplitude_m = 1e-3});
  ASSERT_TRUE(fit.ok);
  EXPECT_NEAR(fit.ModalConstant(), kModalConstant, kExact * kModalConstant);
  const double a = points[4].amplitude_m;
  EXPECT_NEAR(fit.NaturalFrequency_rad_s(a) / (2 * std::numbers::pi), kNaturalFrequency_hz, kExact * kNaturalFrequency_hz);
  EXPECT_NEAR(fit.DampingRatio(a), kDampingRatio, 1e-6 * kDampingRatio);
}

TEST(MeasuredBackbone, FindsALinearOscillatorsResonanceAndDampingByEveryMethod) {
  const MeasuredBackbone m = AnalyseMeasuredBackbone({SdofLevel(1.0), SdofLevel(2.0)});
  ASSERT_EQ(m.levels.size(), 2u);
  for (const auto& l : m.levels) {
    EXPECT_EQ(l.control, LevelControl::kForce);
    EXPECT_NEAR(l.quadrature_frequency_hz.value, kNaturalFrequency_hz, 1e-7 * kNaturalFrequency_hz);
    EXPECT_NEAR(l.quadrature_damping_ratio.value, kDampingRatio, 1e-5 * kDampingRatio);
    EXPECT_NEAR(l.local_damping_ratio.value, kDampingRatio, 1e-5 * kDampingRatio);
    EXPECT_NEAR(l.half_power_damping_ratio.value, kDampingRatio, kHalfPowerBias * kDampingRatio);
    // |X_d/F| peaks at ω_n·√(1 − 2ζ²); a parabola through three steps finds it to 0.5 mHz.
    EXPECT_NEAR(l.peak_frequency_hz.value, kNaturalFrequency_hz * std::sqrt(1 - 2 * kDampingRatio * kDampingRatio), 5e-4);
    EXPECT_LT(l.regeneration_relative_rms, 1e-6);
  }
  // A linear oscillator's amplitude doubles with the force; its damping does not change.
  EXPECT_NEAR(m.levels[1].quadrature_amplitude_m.value, 2 * m.levels[0].quadrature_amplitude_m.value,
              1e-6 * m.levels[1].quadrature_amplitude_m.value);
  EXPECT_NE(m.damping_trend.verdict, "rises");
}

}  // namespace
}  // namespace beamid::solver
