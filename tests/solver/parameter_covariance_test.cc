// The fit's parameter covariance (solver/estimation/parameter_covariance.h)
// against the sandwich written out by hand, A⁻¹·Jᵀ·Σ·J·A⁻¹ for a residual
// covariance Σ that is not the identity, on a Jacobian whose columns span
// twenty orders of magnitude, where inverting A as it stands loses the
// small column's variance.
#include <cmath>
#include <random>

#include <Eigen/Dense>
#include <gtest/gtest.h>

#include "solver/estimation/parameter_covariance.h"

namespace beamid::solver {
namespace {

struct Problem {
  Eigen::MatrixXd jacobian, residual_covariance;
};

// Columns scaled by 1e-10, 1 and 1e10 (a clamp compliance, k1, k3);
// residuals correlated in pairs as a step's channels are.
Problem BadlyScaledProblem() {
  std::mt19937_64 rng(5);
  std::normal_distribution<double> normal;
  Problem p{.jacobian = Eigen::MatrixXd(40, 3), .residual_covariance = Eigen::MatrixXd::Identity(40, 40)};
  for (Eigen::Index i = 0; i < p.jacobian.rows(); ++i)
    for (Eigen::Index j = 0; j < p.jacobian.cols(); ++j) p.jacobian(i, j) = normal(rng) * std::pow(1e10, j - 1.0);
  for (Eigen::Index i = 0; i + 1 < p.residual_covariance.rows(); i += 2)
    p.residual_covariance(i, i + 1) = p.residual_covariance(i + 1, i) = 0.6;
  return p;
}

// The same fit in units where every column is O(1): the reference, since
// there the plain inverse is exact to rounding.
Eigen::MatrixXd SandwichInUnitScale(const Problem& p, const Eigen::MatrixXd& model_error_information, double scale) {
  const Eigen::VectorXd units = p.jacobian.colwise().norm().transpose();
  const Eigen::MatrixXd j = p.jacobian * units.cwiseInverse().asDiagonal();
  const Eigen::MatrixXd inverse = (j.transpose() * j).inverse();
  const Eigen::MatrixXd m = units.cwiseInverse().asDiagonal() * model_error_information * units.cwiseInverse().asDiagonal();
  const Eigen::MatrixXd unit_scale =
      scale * inverse * j.transpose() * p.residual_covariance * j * inverse + inverse * m * inverse;
  return units.cwiseInverse().asDiagonal() * unit_scale * units.cwiseInverse().asDiagonal();
}

TEST(SandwichCovariance, EqualsTheSandwichOfTheResidualsCovarianceAcrossTwentyOrdersOfMagnitude) {
  const Problem p = BadlyScaledProblem();
  const Eigen::MatrixXd shared =
      p.jacobian.transpose() * (p.residual_covariance - Eigen::MatrixXd::Identity(40, 40)) * p.jacobian;
  const Eigen::MatrixXd model_error = 0.2 * p.jacobian.transpose() * p.jacobian;
  const ParameterCovariance c = SandwichCovariance(p.jacobian, shared, model_error, 1.3);
  const Eigen::MatrixXd expected = SandwichInUnitScale(p, model_error, 1.3);
  for (Eigen::Index i = 0; i < 3; ++i)
    for (Eigen::Index j = 0; j < 3; ++j)
      EXPECT_NEAR(c.total(i, j), expected(i, j), 1e-9 * std::sqrt(expected(i, i) * expected(j, j))) << i << "," << j;
  // The model error's share alone: A⁻¹·M·A⁻¹ = 0.2·A⁻¹.
  const Eigen::MatrixXd only_model_error = SandwichInUnitScale(p, model_error, 0.0);
  for (Eigen::Index i = 0; i < 3; ++i) EXPECT_NEAR(c.model_error(i, i), only_model_error(i, i), 1e-9 * only_model_error(i, i));
  EXPECT_FALSE(c.collinear);
  // Correlated residuals that cancel from a parameter narrow it below the
  // count that takes them as independent: the sandwich is not A⁻¹ inflated.
  const ParameterCovariance independent = SandwichCovariance(p.jacobian, Eigen::MatrixXd::Zero(3, 3),
                                                             Eigen::MatrixXd::Zero(3, 3), 1.0);
  bool differs = false;
  for (Eigen::Index i = 0; i < 3; ++i)
    differs |= std::abs(c.total(i, i) - 1.3 * independent.total(i, i)) > 0.05 * c.total(i, i);
  EXPECT_TRUE(differs);
}

TEST(SandwichCovariance, FlagsParametersThatMoveTheResidualsAlike) {
  Problem p = BadlyScaledProblem();
  p.jacobian.col(2) = 3e20 * p.jacobian.col(0);  // the third a rescaled copy of the first
  const ParameterCovariance c =
      SandwichCovariance(p.jacobian, Eigen::MatrixXd::Zero(3, 3), Eigen::MatrixXd::Zero(3, 3), 1.0);
  EXPECT_TRUE(c.collinear);
}

}  // namespace
}  // namespace beamid::solver
