// The one-sided (asymmetric) stiffness law against closed forms: on
// θ = A·cos t its moment k_a·max(θ, 0) is a half-wave rectified cosine,
//     k_a·A·[1/π + cos t/2 + 2cos 2t/(3π) − 2cos 4t/(15π) + …],
// independently of how the harmonic balance samples it; its tangent and
// parameter Jacobian against differences.
#include "hb/support_law.h"

#include <cmath>
#include <complex>
#include <numbers>

#include <gtest/gtest.h>

namespace beamid::hb {
namespace {

constexpr double kTight = 1e-12;

TEST(OneSidedStiffnessLawTest, HalfWaveRectifiedCosineHasItsClosedFormHarmonics) {
  constexpr double kStiffness = 40.0, kAmplitude = 0.01;
  constexpr int kSamples = 1024;  // EvaluatePeriodic builds N × N Jacobians: keep N modest
  const OneSidedStiffnessLaw law(kStiffness);
  Eigen::VectorXd theta(kSamples), rate = Eigen::VectorXd::Zero(kSamples);
  for (int n = 0; n < kSamples; ++n) theta[n] = kAmplitude * std::cos(2.0 * std::numbers::pi * n / kSamples);
  const Eigen::VectorXd moment = law.EvaluatePeriodic(theta, rate).moment_Nm;
  auto cosine_coefficient = [&](int k) {
    double sum = 0.0;
    for (int n = 0; n < kSamples; ++n) sum += moment[n] * std::cos(2.0 * std::numbers::pi * k * n / kSamples);
    return (k == 0 ? 1.0 : 2.0) * sum / kSamples;
  };
  const double scale = kStiffness * kAmplitude;
  // A kink at θ = 0: sampled, the coefficients converge like 1/N².
  constexpr double kSampling = 1e-5;
  EXPECT_NEAR(cosine_coefficient(0), scale / std::numbers::pi, kSampling * scale);
  EXPECT_NEAR(cosine_coefficient(1), scale / 2.0, kSampling * scale);
  EXPECT_NEAR(cosine_coefficient(2), scale * 2.0 / (3.0 * std::numbers::pi), kSampling * scale);
  EXPECT_NEAR(cosine_coefficient(3), 0.0, kSampling * scale);
  EXPECT_NEAR(cosine_coefficient(4), -scale * 2.0 / (15.0 * std::numbers::pi), kSampling * scale);
}

TEST(OneSidedStiffnessLawTest, TangentAndParameterJacobianMatchDifferences) {
  const OneSidedStiffnessLaw law(-25.0);
  for (double theta : {-0.02, -1e-4, 3e-4, 0.015}) {
    const double h = 1e-7;
    const double difference = (law.Evaluate(theta + h, 0.0, {}, {}).moment_Nm -
                               law.Evaluate(theta - h, 0.0, {}, {}).moment_Nm) / (2 * h);
    EXPECT_NEAR(law.Evaluate(theta, 0.0, {}, {}).d_moment_d_theta_Nm_rad, difference, 1e-6);
  }
  Eigen::VectorXd theta(4);
  theta << -0.01, 0.0, 0.002, 0.03;
  const Eigen::MatrixXd jacobian = law.PeriodicParameterJacobian(theta, Eigen::VectorXd::Zero(4));
  OneSidedStiffnessLaw nudged(-25.0 + 1e-3);
  const Eigen::VectorXd difference =
      (nudged.EvaluatePeriodic(theta, Eigen::VectorXd::Zero(4)).moment_Nm -
       law.EvaluatePeriodic(theta, Eigen::VectorXd::Zero(4)).moment_Nm) / 1e-3;
  EXPECT_LT((jacobian.col(0) - difference).norm(), kTight * 1e3);
  EXPECT_EQ(law.Parameters().front().name, "one_sided_stiffness");
}

TEST(OneSidedStiffnessLawTest, ParallelWithThePolynomialThroughTheFactory) {
  const auto law = MakePolynomialSupportLaw({.k1_Nm_rad = 100.0}, std::nullopt, 40.0);
  EXPECT_NEAR(law->Evaluate(0.01, 0.0, {}, {}).moment_Nm, 140.0 * 0.01, kTight);
  EXPECT_NEAR(law->Evaluate(-0.01, 0.0, {}, {}).moment_Nm, -100.0 * 0.01, kTight);
  EXPECT_EQ(law->Parameters().size(), 5u);
}

}  // namespace
}  // namespace beamid::hb
