#include "hb/harmonic_balance.h"

#include <cmath>
#include <cstdio>
#include <numbers>

#include <gtest/gtest.h>

#include "tests/support/paper_setup.h"

namespace beamid::hb {
namespace {

using testing::kForcePosition_m;
using testing::kSensorPositions_m;
using testing::PaperBeam;

constexpr double kK1_Nm_rad = 150.43;  // first resonance at 54.0 Hz
constexpr double kOmega54_rad_s = 2.0 * std::numbers::pi * 54.0;

HarmonicBalance MakeBalance(const PolynomialSupportLaw::Coefficients& k, int harmonics, double loss_factor = 1e-3) {
  BeamProperties beam = PaperBeam();
  beam.loss_factor = loss_factor;
  LinearBeam linear({.beam = beam}, kForcePosition_m);
  return HarmonicBalance(linear, PolynomialSupportLaw(k), {.num_harmonics = harmonics});
}

Eigen::VectorXcd Force(double amplitude_N) {
  Eigen::VectorXcd f = Eigen::VectorXcd::Zero(2);
  f[1] = amplitude_N;
  return f;
}

TEST(HarmonicBalance, LinearLawReproducesTheExactReceptance) {
  // With k2 = k3 = 0 the balance is linear: its θ and sensor motion must equal
  // the direct solution of the whole beam with the spring and dashpot in place.
  const PolynomialSupportLaw::Coefficients k{.k1_Nm_rad = kK1_Nm_rad, .c_Nms_rad = 0.02};
  const HarmonicBalance balance = MakeBalance(k, 3);
  BeamProperties beam = PaperBeam();
  beam.loss_factor = 1e-3;
  LinearBeam direct({.beam = beam, .support_stiffness_Nm_rad = k.k1_Nm_rad, .support_damping_Nms_rad = k.c_Nms_rad},
                    kForcePosition_m);
  const std::vector<double> sensors(std::begin(kSensorPositions_m), std::end(kSensorPositions_m));
  for (double omega : {0.8 * kOmega54_rad_s, kOmega54_rad_s, 1.1 * kOmega54_rad_s}) {
    const auto solution = balance.Solve(omega, Force(1.5));
    ASSERT_TRUE(solution.converged);
    const BeamDeflection exact = direct.RespondToForce(omega);
    EXPECT_LT(std::abs(solution.theta_rad[1] - 1.5 * exact.SupportRotation_rad()),
              1e-9 * std::abs(solution.theta_rad[1]));
    EXPECT_LT(std::abs(solution.theta_rad[3]), 1e-12);
    const Eigen::MatrixXcd y = balance.Displacements(solution, Force(1.5), sensors);
    for (std::size_t i = 0; i < sensors.size(); ++i)
      EXPECT_LT(std::abs(y(i, 1) - 1.5 * exact.Displacement_m(sensors[i])), 1e-9 * std::abs(y(i, 1)));
  }
}

TEST(HarmonicBalance, AnalyticJacobianMatchesCentralDifferences) {
  const HarmonicBalance balance =
      MakeBalance({.k1_Nm_rad = kK1_Nm_rad, .k2_Nm_rad2 = 3e3, .k3_Nm_rad3 = 4e5, .c_Nms_rad = 0.02}, 5);
  Eigen::VectorXd z = Eigen::VectorXd::Random(balance.num_unknowns()) * 5e-3;  // fixed seed (Eigen's rand)
  const LinearHarmonics linear = balance.Linear(kOmega54_rad_s);
  Eigen::VectorXd r, dr_domega;
  Eigen::MatrixXd j;
  balance.Residual(z, linear, Force(2.0), &r, &j, &dr_domega);
  double worst = 0.0;
  for (int i = 0; i < balance.num_unknowns(); ++i) {
    const double h = 1e-7;
    Eigen::VectorXd up = z, down = z, r_up, r_down;
    up[i] += h;
    down[i] -= h;
    balance.Residual(up, linear, Force(2.0), &r_up);
    balance.Residual(down, linear, Force(2.0), &r_down);
    const Eigen::VectorXd column = (r_up - r_down) / (2 * h);
    worst = std::max(worst, (column - j.col(i)).norm() / j.norm());
  }
  EXPECT_LT(worst, 1e-7) << "worst relative column error";
  const double h = 1e-3;
  Eigen::VectorXd r_up, r_down;
  balance.Residual(z, balance.Linear(kOmega54_rad_s + h), Force(2.0), &r_up);
  balance.Residual(z, balance.Linear(kOmega54_rad_s - h), Force(2.0), &r_down);
  // ∂R/∂ω is a documented forward difference of the linear part (~1e-6).
  EXPECT_LT(((r_up - r_down) / (2 * h) - dr_domega).norm(), 1e-5 * dr_domega.norm());
}

TEST(HarmonicBalance, ForcePhaseShiftRotatesEveryHarmonic) {
  // Shifting time by τ multiplies harmonic k by e^{ikωτ}: a force phase of φ
  // must give Θ_k·e^{ikφ}.
  const HarmonicBalance balance =
      MakeBalance({.k1_Nm_rad = kK1_Nm_rad, .k2_Nm_rad2 = 5e3, .k3_Nm_rad3 = 4e5, .c_Nms_rad = 0.02}, 5);
  const auto reference = balance.Solve(kOmega54_rad_s, Force(2.0));
  const double phi = 0.7;
  const auto shifted = balance.Solve(kOmega54_rad_s, Force(2.0) * std::polar(1.0, phi));
  ASSERT_TRUE(reference.converged && shifted.converged);
  for (int k = 0; k <= 5; ++k) {
    const Complex expected = reference.theta_rad[k] * std::polar(1.0, k * phi);
    EXPECT_LT(std::abs(shifted.theta_rad[k] - expected), 1e-8 * std::abs(reference.theta_rad[1])) << "k = " << k;
  }
}

TEST(HarmonicBalance, ConvergesAsHarmonicsAreAdded) {
  // Strongly nonlinear level: resonance shifted by several per cent, θ ≈ 15 mrad.
  const PolynomialSupportLaw::Coefficients k{.k1_Nm_rad = kK1_Nm_rad, .k2_Nm_rad2 = 2e4, .k3_Nm_rad3 = 1.5e6,
                                             .c_Nms_rad = 0.02};
  const std::vector<double> sensors(std::begin(kSensorPositions_m), std::end(kSensorPositions_m));
  const double omega = 1.04 * kOmega54_rad_s;
  Eigen::MatrixXcd previous;
  std::vector<double> change_first, change_third;
  for (int h : {3, 5, 7, 9, 11}) {
    const HarmonicBalance balance = MakeBalance(k, h);
    const auto solution = balance.Solve(omega, Force(3.0));
    ASSERT_TRUE(solution.converged) << "H = " << h;
    const Eigen::MatrixXcd y = balance.Displacements(solution, Force(3.0), sensors);
    if (h == 7) previous = y;
    if (h == 11) {
      for (int i = 0; i < 3; ++i) {
        EXPECT_LT(std::abs(y(i, 1) - previous(i, 1)), 1e-3 * std::abs(y(i, 1))) << "sensor " << i;
        EXPECT_LT(std::abs(y(i, 3) - previous(i, 3)), 1e-3 * std::abs(y(i, 3))) << "sensor " << i;
      }
      EXPECT_GT(std::abs(y(2, 3)), 1e-3 * std::abs(y(2, 1))) << "the level must be strongly nonlinear";
    }
  }
}

TEST(HarmonicBalance, AOneSidedSupportIsSampledDenselyEnough) {
  // M = k_a·max(θ, 0) has a kink: its harmonics decay like 1/k² and alias in
  // the alternating frequency–time step. With the automatic sampling the
  // five-harmonic balance must agree with one sampled 1024 times per period
  // (aliasing ~1000× smaller) on the fundamental and the even harmonics.
  BeamProperties beam = PaperBeam();
  beam.loss_factor = 1e-3;
  const LinearBeam linear({.beam = beam}, kForcePosition_m);
  const auto law = MakePolynomialSupportLaw({.k1_Nm_rad = 120.0, .k3_Nm_rad3 = 3e5, .c_Nms_rad = 0.02}, std::nullopt,
                                            60.0);
  EXPECT_FALSE(law->IsSmooth());
  const HarmonicBalance automatic(linear, *law, {.num_harmonics = 5});
  const HarmonicBalance dense(linear, *law, {.num_harmonics = 5, .num_time_samples = 1024});
  const double omega = 0.98 * kOmega54_rad_s;
  const auto a = automatic.Solve(omega, Force(4.0));
  const auto d = dense.Solve(omega, Force(4.0));
  ASSERT_TRUE(a.converged && d.converged);
  std::printf("N = %d: |dTheta1|/|Theta1| = %.3g, |dTheta2|/|Theta2| = %.3g (|Theta2|/|Theta1| = %.3g)\n",
              automatic.num_time_samples(), std::abs(a.theta_rad[1] - d.theta_rad[1]) / std::abs(d.theta_rad[1]),
              std::abs(a.theta_rad[2] - d.theta_rad[2]) / std::abs(d.theta_rad[2]),
              std::abs(d.theta_rad[2]) / std::abs(d.theta_rad[1]));
  EXPECT_GT(std::abs(d.theta_rad[2]), 0.005 * std::abs(d.theta_rad[1])) << "the asymmetry must show";
  EXPECT_LT(std::abs(a.theta_rad[1] - d.theta_rad[1]), 1e-4 * std::abs(d.theta_rad[1]));
  EXPECT_LT(std::abs(a.theta_rad[2] - d.theta_rad[2]), 1e-3 * std::abs(d.theta_rad[2]));
}

TEST(HarmonicBalance, JenkinsSticksLinearlyAndSlipsWithDissipation) {
  BeamProperties beam = PaperBeam();
  beam.loss_factor = 1e-3;
  LinearBeam linear({.beam = beam}, kForcePosition_m);
  CompositeSupportLaw law;
  law.Add(std::make_unique<PolynomialSupportLaw>(PolynomialSupportLaw::Coefficients{.k1_Nm_rad = 100.0}));
  law.Add(std::make_unique<JenkinsSupportLaw>(JenkinsSupportLaw::Parameters_{.stiffness_Nm_rad = 50.43,
                                                                             .slip_moment_Nm = 0.005}));
  const HarmonicBalance balance(linear, law, {.num_harmonics = 7});
  // Tiny force: sticks, so it equals the linear beam with k1 = 150.43.
  LinearBeam stuck({.beam = beam, .support_stiffness_Nm_rad = kK1_Nm_rad}, kForcePosition_m);
  const auto small = balance.Solve(0.95 * kOmega54_rad_s, Force(0.01));
  ASSERT_TRUE(small.converged);
  EXPECT_LT(std::abs(small.theta_rad[1] - 0.01 * stuck.RespondToForce(0.95 * kOmega54_rad_s).SupportRotation_rad()),
            1e-9 * std::abs(small.theta_rad[1]));
  // Large force: the slider slips and the support dissipates. The energy per
  // cycle from the harmonics, W = π Σ k·Im(M_k·conj Θ_k), must equal the area
  // of the loop traced by stepping the same law incrementally in time along
  // the solution's θ(t) (the simulator's path, independent of the AFT one).
  const auto large = balance.Solve(0.95 * kOmega54_rad_s, Force(2.0));
  ASSERT_TRUE(large.converged);
  const Eigen::VectorXcd moment = balance.SupportMoment(large);
  double energy_harmonics = 0.0;
  for (int k = 1; k <= 7; ++k)
    energy_harmonics += std::numbers::pi * k * std::imag(moment[k] * std::conj(large.theta_rad[k]));
  const JenkinsSupportLaw jenkins({.stiffness_Nm_rad = 50.43, .slip_moment_Nm = 0.005});
  auto theta_at = [&](double phase) {
    double value = large.theta_rad[0].real();
    for (int k = 1; k <= 7; ++k) value += std::real(large.theta_rad[k] * std::polar(1.0, k * phase));
    return value;
  };
  constexpr int kSteps = 20000;
  double slider = 0.0, energy_loop = 0.0, previous_theta = theta_at(0.0), previous_moment = 0.0;
  for (int cycle = 0; cycle < 3; ++cycle) {
    energy_loop = 0.0;
    for (int i = 1; i <= kSteps; ++i) {
      const double theta = theta_at(2.0 * std::numbers::pi * i / kSteps);
      double next_slider = slider;
      const double m = jenkins.Evaluate(theta, 0.0, {&slider, 1}, {&next_slider, 1}).moment_Nm;
      energy_loop += 0.5 * (m + previous_moment) * (theta - previous_theta);
      slider = next_slider;
      previous_theta = theta;
      previous_moment = m;
    }
  }
  const double amplitude = std::abs(large.theta_rad[1]);
  ASSERT_GT(50.43 * amplitude, 2.0 * 0.005) << "the level must slip";
  EXPECT_GT(energy_loop, 0.0);
  EXPECT_NEAR(energy_harmonics, energy_loop, 0.02 * energy_loop);
}

}  // namespace
}  // namespace beamid::hb

namespace beamid::hb {
namespace {

TEST(HarmonicBalance, ParameterJacobianMatchesCentralDifferences) {
  // For the polynomial law (exact columns) and the Jenkins element (default
  // differences of the periodic loop), against re-evaluated residuals.
  BeamProperties beam = testing::PaperBeam();
  CompositeSupportLaw law;
  law.Add(std::make_unique<PolynomialSupportLaw>(
      PolynomialSupportLaw::Coefficients{.k1_Nm_rad = 100.0, .k2_Nm_rad2 = 3e3, .k3_Nm_rad3 = 4e5, .c_Nms_rad = 0.02}));
  law.Add(std::make_unique<JenkinsSupportLaw>(JenkinsSupportLaw::Parameters_{.stiffness_Nm_rad = 50.0,
                                                                             .slip_moment_Nm = 0.02}));
  HarmonicBalance balance(LinearBeam({.beam = beam}, testing::kForcePosition_m), law, {.num_harmonics = 5});
  Eigen::VectorXd z = Eigen::VectorXd::Zero(balance.num_unknowns());
  z[1] = 2e-3;
  z[2] = -1e-3;
  z[5] = 2e-4;
  const double omega = 2.0 * std::numbers::pi * 54.0;
  const LinearHarmonics linear = balance.Linear(omega);
  Eigen::VectorXcd force = Eigen::VectorXcd::Zero(2);
  force[1] = 1.0;
  const Eigen::MatrixXd analytic = balance.ParameterJacobian(z, omega);
  std::vector<double> values;
  for (const auto& p : law.Parameters()) values.push_back(p.value);
  for (std::size_t j = 0; j < values.size(); ++j) {
    const double h = 1e-5 * values[j];
    std::vector<double> up = values, down = values;
    up[j] += h;
    down[j] -= h;
    Eigen::VectorXd r_up, r_down;
    balance.SetLawParameters(up);
    balance.Residual(z, linear, force, &r_up);
    balance.SetLawParameters(down);
    balance.Residual(z, linear, force, &r_down);
    const Eigen::VectorXd numeric = (r_up - r_down) / (2 * h);
    EXPECT_LT((numeric - analytic.col(j)).norm(), 1e-6 * (numeric.norm() + 1e-12)) << "parameter " << j;
  }
}

}  // namespace
}  // namespace beamid::hb
