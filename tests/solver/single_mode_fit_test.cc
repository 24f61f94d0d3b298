// Known answers: a linear single-degree-of-freedom oscillator's exact
// receptance X/F = A/(ω_n² − ω² + 2iζω_nω) (closed form, not the model of
// the beam) must give back ω_n, ζ and A from the single-mode fit, and the
// measured-backbone analysis must find its phase resonance and damping by
// all three methods. A nonlinear mode in closed form — microslip power laws
// for stiffness and damping, a complex modal constant that changes with
// amplitude — must give back its exponents, A(a) and its phase resonances.
#include "solver/backbone/single_mode_fit.h"

#include <cmath>
#include <complex>
#include <numbers>

#include <gtest/gtest.h>

#include "signal/first_harmonic_level.h"
#include "solver/backbone/measured_backbone.h"

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
  EXPECT_EQ(m.damping_trend.verdict, Trend::kNone);
}

// A nonlinear mode in closed form: ω_n²(a) = p0 + p1·s^α (softening, α = 1.5),
// ζω_n(a) = q0 + q1·s^β (β = 0.5: dissipation per cycle ∝ a^2.5, the microslip
// regime of Iwan/Segalman joints), A(a) = A0 + i·A_i + A2·s², s = a/a_ref.
constexpr double kAlpha = 1.5, kBeta = 0.5, kReferenceAmplitude_m = 1e-3;
constexpr double kModalConstantImag = -0.08, kModalConstantSlope = -0.05;  // A_i, A2 [1/kg]
const double kOmega0 = 2 * std::numbers::pi * kNaturalFrequency_hz;
const double kP0 = kOmega0 * kOmega0, kP1 = -0.02 * kP0;
const double kQ0 = kDampingRatio * kOmega0, kQ1 = 0.8 * kQ0;

std::complex<double> IwanModalConstant(double a) {
  const double s = a / kReferenceAmplitude_m;
  return {kModalConstant + kModalConstantSlope * s * s, kModalConstantImag};
}

// G = F/X_d = D(a, ω)/A(a) at a chosen amplitude and frequency.
std::complex<double> IwanInverseReceptance(double a, double omega) {
  const double s = a / kReferenceAmplitude_m;
  const std::complex<double> d(kP0 + kP1 * std::pow(s, kAlpha) - omega * omega, 2 * omega * (kQ0 + kQ1 * std::pow(s, kBeta)));
  return d / IwanModalConstant(a);
}

// Response-controlled levels (a held at each level's value) sweeping through the resonance.
std::vector<signal::FirstHarmonicLevel> IwanLevels() {
  std::vector<signal::FirstHarmonicLevel> levels;
  for (double a : {0.2e-3, 0.4e-3, 0.6e-3, 0.8e-3, 1.0e-3}) {
    signal::FirstHarmonicLevel level{.label = "a" + std::to_string(a), .source = "closed form",
                                     .response_quantity = signal::Quantity::kDisplacement};
    for (double f = 53.0; f <= 55.01; f += 0.2) {
      const std::complex<double> g = IwanInverseReceptance(a, 2 * std::numbers::pi * f);
      signal::FirstHarmonicPoint p{.frequency_hz = f};
      p.response.value = a;
      p.force.value = a * g;
      level.points.push_back(p);
    }
    levels.push_back(level);
  }
  return levels;
}

TEST(SingleModeFit, RecoversAnIwanLikeModeWithAComplexAmplitudeDependentModalConstant) {
  std::vector<SingleModePoint> points;
  for (const auto& level : IwanLevels())
    for (const auto& p : level.points)
      points.push_back({.omega_rad_s = 2 * std::numbers::pi * p.frequency_hz,
                        .inverse_receptance_N_m = p.force.value / p.response.value,
                        .amplitude_m = std::abs(p.response.value)});
  const SingleModeFit fit = FitSingleModeChoosingExponents(
      points, {.frequency_exponent = 1.0, .damping_exponent = 1.0, .amplitude_dependent_modal_constant = true,
               .reference_amplitude_m = kReferenceAmplitude_m});
  ASSERT_TRUE(fit.ok);
  EXPECT_EQ(fit.frequency_exponent, kAlpha);
  EXPECT_EQ(fit.damping_exponent, kBeta);
  EXPECT_EQ(fit.NumParameters(), 3 + 2 + 2 + 2);  // A0 (complex), A2, p0, p1, q0, q1, α, β
  for (double a : {0.3e-3, 0.9e-3}) {
    EXPECT_NEAR(std::abs(fit.ModalConstantAt(a) - IwanModalConstant(a)), 0.0, kExact * kModalConstant);
    const double s = a / kReferenceAmplitude_m;
    EXPECT_NEAR(fit.NaturalFrequency_rad_s(a), std::sqrt(kP0 + kP1 * std::pow(s, kAlpha)), kExact * kOmega0);
  }
  // A broken power law (the wrong exponent) must not fit exactly.
  const SingleModeFit wrong = FitSingleMode(
      points, {.frequency_exponent = 2.0, .damping_exponent = kBeta, .amplitude_dependent_modal_constant = true,
               .reference_amplitude_m = kReferenceAmplitude_m});
  EXPECT_GT(wrong.chi_square, 1e6 * fit.chi_square + 1e-12);
}

TEST(MeasuredBackbone, ChoosesThePowerLawsOfAnIwanLikeModeAndFindsItsPhaseResonances) {
  const MeasuredBackbone m = AnalyseMeasuredBackbone(IwanLevels());
  ASSERT_TRUE(m.fit.ok);
  EXPECT_EQ(m.fit.frequency_exponent, kAlpha) << m.fit.FormName();
  EXPECT_EQ(m.fit.damping_exponent, kBeta) << m.fit.FormName();
  EXPECT_TRUE(m.fit.amplitude_dependent_modal_constant);
  for (const auto& l : m.levels) {
    EXPECT_EQ(l.control, LevelControl::kResponse);
    EXPECT_LT(l.regeneration_relative_rms, 1e-6) << l.label;
    // The response is in quadrature with the force where Re(A·D̄) = 0: bisection on the closed form.
    const double a = l.quadrature_amplitude_m.value;
    double lo = 2 * std::numbers::pi * 53.0, hi = 2 * std::numbers::pi * 55.0;
    for (int it = 0; it < 100; ++it) {
      const double mid = 0.5 * (lo + hi);
      ((1.0 / IwanInverseReceptance(a, mid)).real() > 0 ? lo : hi) = mid;
    }
    EXPECT_NEAR(l.quadrature_frequency_hz.value, lo / (2 * std::numbers::pi), 1e-7 * kNaturalFrequency_hz) << l.label;
  }
  // ζω_n itself rises (q1·s^β): beyond what a constant damper gives.
  EXPECT_EQ(m.damping_trend.verdict, Trend::kRises);
}

}  // namespace
}  // namespace beamid::solver
