#include "hb/continuation.h"

#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "hb/backbone.h"
#include "tests/support/paper_setup.h"

namespace beamid::hb {
namespace {

using testing::kForcePosition_m;
using testing::PaperBeam;

constexpr double kK1_Nm_rad = 150.43;
constexpr double kOmega54_rad_s = 2.0 * std::numbers::pi * 54.0;

HarmonicBalance MakeBalance(const PolynomialSupportLaw::Coefficients& k, int harmonics) {
  BeamProperties beam = PaperBeam();
  beam.loss_factor = 1e-3;
  return HarmonicBalance(LinearBeam({.beam = beam}, kForcePosition_m), PolynomialSupportLaw(k),
                         {.num_harmonics = harmonics});
}

Eigen::VectorXcd Force(double amplitude_N) {
  Eigen::VectorXcd f = Eigen::VectorXcd::Zero(2);
  f[1] = amplitude_N;
  return f;
}

TEST(Continuation, PassesTheTurningPointsOfASofteningCurveAndFindsBothBranches) {
  const HarmonicBalance balance =
      MakeBalance({.k1_Nm_rad = kK1_Nm_rad, .k3_Nm_rad3 = -4e5, .c_Nms_rad = 0.01}, 5);
  const auto summary = TraceFrequencyResponse(
      balance, Force(1.5),
      {.omega_start_rad_s = 1.03 * kOmega54_rad_s, .omega_end_rad_s = 0.90 * kOmega54_rad_s, .max_points = 2000});
  ASSERT_TRUE(summary.reached_end) << summary.message;
  EXPECT_EQ(summary.num_turning_points, 2);
  // Every point solves the equations.
  for (const auto& p : summary.points) {
    Eigen::VectorXd r;
    balance.Residual(HarmonicBalance::ToReal(p.theta_rad), balance.Linear(p.omega_rad_s), Force(1.5), &r);
    ASSERT_LT(r.norm(), 1e-7 * (1.0 + std::abs(p.theta_rad[1]) * kK1_Nm_rad));
  }
  // Inside the hysteresis a frequency has three solutions: the middle one is
  // unstable, the outer two stable, and independent Newton solves started
  // from each branch confirm them.
  std::vector<std::size_t> unstable;
  for (std::size_t i = 0; i + 1 < summary.points.size(); ++i)
    if (!summary.points[i].stable && !summary.points[i + 1].stable) unstable.push_back(i);
  ASSERT_FALSE(unstable.empty());
  const std::size_t middle = unstable[unstable.size() / 2];
  // Between two points of the unstable branch, so no point sits exactly on it.
  const double omega_inside = 0.5 * (summary.points[middle].omega_rad_s + summary.points[middle + 1].omega_rad_s);
  std::vector<double> amplitudes;
  for (std::size_t i = 1; i < summary.points.size(); ++i) {
    const auto& a = summary.points[i - 1];
    const auto& b = summary.points[i];
    if ((a.omega_rad_s - omega_inside) * (b.omega_rad_s - omega_inside) < 0.0) {
      const auto solution = balance.Solve(omega_inside, Force(1.5), HarmonicBalance::ToReal(a.theta_rad));
      ASSERT_TRUE(solution.converged);
      amplitudes.push_back(std::abs(solution.theta_rad[1]));
    }
  }
  ASSERT_EQ(amplitudes.size(), 3u);
  std::sort(amplitudes.begin(), amplitudes.end());
  EXPECT_GT(amplitudes[1] - amplitudes[0], 0.05 * amplitudes[2]);
  EXPECT_GT(amplitudes[2] - amplitudes[1], 0.05 * amplitudes[2]);
}

TEST(Continuation, LinearCurvePeaksAtTheNaturalFrequency) {
  const HarmonicBalance balance = MakeBalance({.k1_Nm_rad = kK1_Nm_rad, .c_Nms_rad = 0.005}, 3);
  const auto summary = TraceFrequencyResponse(
      balance, Force(0.5), {.omega_start_rad_s = 0.95 * kOmega54_rad_s, .omega_end_rad_s = 1.05 * kOmega54_rad_s});
  ASSERT_TRUE(summary.reached_end);
  EXPECT_EQ(summary.num_turning_points, 0);
  double peak = 0.0, omega_peak = 0.0;
  for (const auto& p : summary.points) {
    EXPECT_TRUE(p.stable);
    if (std::abs(p.theta_rad[1]) > peak) {
      peak = std::abs(p.theta_rad[1]);
      omega_peak = p.omega_rad_s;
    }
  }
  EXPECT_NEAR(omega_peak, kOmega54_rad_s, 2e-3 * kOmega54_rad_s);
}

TEST(Backbone, ConservativeCubicLawFollowsTheSingleModeAsymptote) {
  // With c = 0 and η = 0 the phase-resonance force vanishes (free periodic
  // motion). At small amplitude the one-mode Duffing reduction gives
  // ω² − ω0² = (3/4)·k3·w'(L)²·a²/m_q for a θ amplitude a, with w the linear
  // mode and m_q = ρA∫w² — computed here from the linear beam alone.
  const BeamProperties beam = PaperBeam();
  constexpr double kK3 = 4e5;
  LinearBeam linear({.beam = beam, .support_stiffness_Nm_rad = kK1_Nm_rad}, kForcePosition_m);
  const double omega0 = linear.NaturalFrequencies_rad_s(1)[0];
  const BeamDeflection mode = linear.ModeShape(0);
  constexpr int kIntervals = 4000;
  double integral = 0.0;
  for (int i = 0; i <= kIntervals; ++i) {
    const double weight = (i == 0 || i == kIntervals) ? 1.0 : (i % 2 ? 4.0 : 2.0);
    integral += weight * std::norm(mode.Displacement_m(beam.length_m * i / kIntervals));
  }
  const double modal_mass = beam.MassPerLength_kg_m() * integral * beam.length_m / (3.0 * kIntervals);
  const double slope = mode.SupportRotation_rad().real();

  const HarmonicBalance balance(LinearBeam({.beam = beam}, kForcePosition_m),
                                PolynomialSupportLaw({.k1_Nm_rad = kK1_Nm_rad, .k3_Nm_rad3 = kK3}),
                                {.num_harmonics = 5});
  const auto summary = TraceBackbone(balance, {.min_theta_amplitude_rad = 1e-5, .max_theta_amplitude_rad = 2e-4,
                                               .num_points = 10});
  ASSERT_TRUE(summary.complete) << summary.message;
  for (const auto& p : summary.points) EXPECT_LT(std::abs(p.force_amplitude_N), 1e-9);
  const auto& last = summary.points.back();
  const double a = last.theta_amplitude_rad;
  const double predicted = 0.75 * kK3 * slope * slope * a * a / modal_mass;
  const double computed = last.omega_rad_s * last.omega_rad_s - omega0 * omega0;
  EXPECT_NEAR(computed, predicted, 0.01 * predicted);
}

TEST(Backbone, PhaseResonancePointsLieOnTheFrequencyResponseCurves) {
  // The backbone with damping passes through the point of each forced curve
  // where θ is in quadrature with the force.
  const HarmonicBalance balance =
      MakeBalance({.k1_Nm_rad = kK1_Nm_rad, .k3_Nm_rad3 = 4e5, .c_Nms_rad = 0.02}, 5);
  const auto backbone = TraceBackbone(balance, {.min_theta_amplitude_rad = 1e-4, .max_theta_amplitude_rad = 1e-2,
                                                .num_points = 30});
  ASSERT_TRUE(backbone.complete);
  const auto& point = backbone.points[25];
  const double force = point.force_amplitude_N;
  const auto solution = balance.Solve(point.omega_rad_s, Force(force), HarmonicBalance::ToReal(point.theta_rad));
  ASSERT_TRUE(solution.converged);
  EXPECT_NEAR(std::abs(solution.theta_rad[1]), point.theta_amplitude_rad, 1e-8 * point.theta_amplitude_rad);
  EXPECT_LT(std::abs(std::real(solution.theta_rad[1] / Complex(force))), 1e-8 * std::abs(solution.theta_rad[1] / force));
}

}  // namespace
}  // namespace beamid::hb
