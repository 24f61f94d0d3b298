// The propagated uncertainty of a response phasor (solver/estimation/
// phasor_uncertainty.h), checked against closed forms: the slope ∂Y/∂ω of
// a single linear mode's receptance, derived by hand, and the covariance of
// Y when the force's amplitude alone is wrong, by Monte Carlo.
#include <cmath>
#include <complex>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "solver/estimation/phasor_uncertainty.h"

namespace beamid::solver {
namespace {

using Complex = std::complex<double>;

// One linear mode: Y = A / (ω_r² − ω² + i·b·ω), dY/dω = −Y²·(−2ω + i·b)/A.
struct Mode {
  double omega_r = 2.0 * 3.141592653589793 * 54.0;
  double b = 2.0 * 0.001 * 2.0 * 3.141592653589793 * 54.0;  // ζ = 0.1 %: half-power band 0.108 Hz
  Complex a = Complex(3.0, -1.0);
  Complex Y(double w) const { return a / Complex(omega_r * omega_r - w * w, b * w); }
  Complex Slope(double w) const { return -Y(w) * Y(w) * Complex(-2.0 * w, b) / a; }
};

std::vector<double> Steps(double first_hz, double step_hz, int n) {
  std::vector<double> omega;
  for (int i = 0; i < n; ++i) omega.push_back(2.0 * 3.141592653589793 * (first_hz + step_hz * i));
  return omega;
}

TEST(NeighbourSlope, EqualsTheSingleModeDerivativeAtEveryStepOfAResonanceNarrowerThanTheSteps) {
  const Mode mode;
  // Steps of 0.25 Hz, more than twice the half-power band; one lands 0.01 Hz
  // from the peak.
  const std::vector<double> omega = Steps(52.51, 0.25, 15);
  std::vector<Complex> values;
  for (const double w : omega) values.push_back(mode.Y(w));
  const std::vector<double> noise(omega.size(), 0.0);
  for (std::size_t i = 1; i + 1 < omega.size(); ++i) {
    const Complex exact = mode.Slope(omega[i]);
    // 1/Y is a parabola in ω: the three-point parabola is exact.
    EXPECT_NEAR(std::abs(NeighbourSlope(omega, values, noise, i) - exact) / std::abs(exact), 0.0, 1e-9)
        << "step " << i;
  }
  // Near the peak a chord of Y itself is several times below the slope:
  // what the parabola of 1/Y is for.
  const std::size_t peak = 6;  // 54.01 Hz
  const Complex chord = (values[peak + 1] - values[peak]) / (omega[peak + 1] - omega[peak]);
  EXPECT_GT(std::abs(mode.Slope(omega[peak])), 4.0 * std::abs(chord));  // measured 4.8
  // At either end of a level the chord of 1/Y is first order in the step.
  const Complex first = mode.Slope(omega.front());
  EXPECT_NEAR(std::abs(NeighbourSlope(omega, values, noise, 0) - first) / std::abs(first), 0.0, 0.2);
}

TEST(NeighbourSlope, AHarmonicAtTheNoiseOrAtZeroTakesTheSmallerChordAndRepeatedFrequenciesHaveNoSlope) {
  const std::vector<double> omega = {100.0, 101.0, 103.0};
  const std::vector<Complex> values = {Complex(1e-6, 0.0), Complex(2e-6, 0.0), Complex(0.0, 1e-6)};
  const std::vector<double> noise(3, 1e-6);
  // Chords from step 1: −1e-6 / −1 and (−2e-6 + 1e-6 i) / 2.
  EXPECT_NEAR(std::abs(NeighbourSlope(omega, values, noise, 1) - Complex(1e-6, 0.0)), 0.0, 1e-18);
  // Noise-free data: a harmonic that is exactly 0 has no 1/Y.
  const std::vector<double> none(3, 0.0);
  const std::vector<Complex> zero_beside = {Complex(1.0, 0.0), Complex(0.0), Complex(2.0, 0.0)};
  EXPECT_EQ(NeighbourSlope(omega, zero_beside, none, 0), Complex(-1.0, 0.0));
  const std::vector<double> dwell = {100.0, 100.0};
  EXPECT_EQ(NeighbourSlope(dwell, {Complex(1.0), Complex(1.1)}, {0.0, 0.0}, 0), Complex(0.0));
  EXPECT_EQ(NeighbourSlope({100.0}, {Complex(1.0)}, {0.0}, 0), Complex(0.0));
}

TEST(PhasorCovariance, TheForceTermIsTheScatterOfAResponseDrivenByAForceWhoseAmplitudeIsWrong) {
  // Y_3 ∝ |F|³ (the cubic's third harmonic at leading order): with |F|
  // scattered by u_F, Y_3 scatters along itself by 3·u_F.
  const Complex y(2.0e-3, -1.5e-3);
  const double u_f = 2e-3;
  std::mt19937 random(7);
  std::normal_distribution<double> normal;
  Eigen::Matrix2d scatter = Eigen::Matrix2d::Zero();
  constexpr int kDraws = 200000;
  for (int n = 0; n < kDraws; ++n) {
    const Complex d = y * (std::pow(1.0 + u_f * normal(random), 3) - 1.0);
    const Eigen::Vector2d v(d.real(), d.imag());
    scatter += v * v.transpose() / kDraws;
  }
  PhasorUncertaintyBudget budget;
  const Eigen::Matrix2d covariance =
      PhasorCovariance({y, Eigen::Matrix2d::Zero()}, 3, u_f, Complex(0.0), 0.0, 0.0, 0.0, &budget);
  EXPECT_NEAR((covariance - scatter).norm() / scatter.norm(), 0.0, 0.01);
  EXPECT_NEAR(budget.force, std::sqrt(0.5 * scatter.trace()), 0.01 * budget.force);
  EXPECT_EQ(budget.noise, 0.0);
  EXPECT_EQ(budget.frequency, 0.0);
}

TEST(PhasorCovariance, EachTermAddsItsOwnVarianceAndTheBudgetNamesIt) {
  const Complex y(3.0, 4.0);  // |Y| = 5
  const Eigen::Matrix2d noise = (Eigen::Matrix2d() << 4e-6, 1e-6, 1e-6, 2e-6).finished();
  const Complex slope(0.0, 2.0);
  PhasorUncertaintyBudget budget;
  const Eigen::Matrix2d covariance = PhasorCovariance({y, noise}, 1, 1e-3, slope, 5e-4, 1e-4, 0.0, &budget);
  Eigen::Matrix2d expected = noise;
  expected += 1e-6 * (Eigen::Matrix2d() << 9.0, 12.0, 12.0, 16.0).finished();   // (u_F)²·y·yᵀ
  expected(1, 1) += 25e-8 * 4.0;                                                 // σ_ω²·g·gᵀ
  expected += 25e-8 * Eigen::Matrix2d::Identity();                               // (ε·|Y|)²
  EXPECT_NEAR((covariance - expected).norm(), 0.0, 1e-15);
  EXPECT_NEAR(budget.noise, std::sqrt(3e-6), 1e-15);
  EXPECT_NEAR(budget.force, 5e-3 / std::sqrt(2.0), 1e-15);
  EXPECT_NEAR(budget.frequency, 1e-3 / std::sqrt(2.0), 1e-15);
  EXPECT_NEAR(budget.model_error, 5e-4, 1e-15);
  // The terms are independent: their variances add up to the whole.
  EXPECT_NEAR(std::sqrt(budget.noise * budget.noise + budget.force * budget.force +
                        budget.frequency * budget.frequency + budget.model_error * budget.model_error),
              std::sqrt(0.5 * covariance.trace()), 1e-15);
}

}  // namespace
}  // namespace beamid::solver
