// The bounded Gauss–Newton step against its closed form: on J = I the
// unconstrained step is −r; a parameter that step would carry through its
// bound moves onto the bound and stays, and a correlated parameter's step
// takes up what the held one cannot.
#include "solver/estimation/gauss_newton_polish.h"

#include <gtest/gtest.h>

namespace beamid::solver {
namespace {

TEST(BoundedGaussNewtonStep, IsTheLeastSquaresStepInsideTheBounds) {
  const Eigen::MatrixXd j = Eigen::MatrixXd::Identity(2, 2);
  const Eigen::Vector2d r(1.0, -2.0);
  const Eigen::VectorXd dp = BoundedGaussNewtonStep(j, r, {5.0, 5.0}, {{0.0, 10.0}, {0.0, 10.0}});
  EXPECT_NEAR(dp[0], -1.0, 1e-12);
  EXPECT_NEAR(dp[1], 2.0, 1e-12);
}

TEST(BoundedGaussNewtonStep, HoldsAParameterAtTheBoundItsStepWouldCross) {
  const Eigen::MatrixXd j = Eigen::MatrixXd::Identity(2, 2);
  const Eigen::Vector2d r(1.0, -2.0);
  // The first would go to 0.5 − 1 < 0: it stops at 0, the second is free.
  const Eigen::VectorXd dp = BoundedGaussNewtonStep(j, r, {0.5, 5.0}, {{0.0, 10.0}, {0.0, 10.0}});
  EXPECT_NEAR(dp[0], -0.5, 1e-12);
  EXPECT_NEAR(dp[1], 2.0, 1e-12);
  // An upper bound likewise.
  const Eigen::VectorXd up = BoundedGaussNewtonStep(j, r, {5.0, 9.0}, {{0.0, 10.0}, {0.0, 10.0}});
  EXPECT_NEAR(up[1], 1.0, 1e-12);
}

TEST(BoundedGaussNewtonStep, TheFreeParametersAnswerWhatTheHeldOneLeaves) {
  // r(p) = J·p − b with correlated columns; the unconstrained optimum has
  // p0 < 0. With p0 held at 0 the best p1 is the 1-D least squares of
  // column 1 against b.
  Eigen::MatrixXd j(3, 2);
  j << 1.0, 1.0, 1.0, 2.0, 1.0, 3.0;
  const Eigen::Vector3d b(0.0, 1.0, 2.0);  // exactly p = (−1, 1)
  const std::vector<double> p{0.0, 0.0};
  const Eigen::VectorXd r = j * Eigen::Vector2d(p[0], p[1]) - b;
  const Eigen::VectorXd dp = BoundedGaussNewtonStep(j, r, p, {{0.0, 10.0}, {-10.0, 10.0}});
  EXPECT_NEAR(dp[0], 0.0, 1e-12);
  EXPECT_NEAR(dp[1], j.col(1).dot(b) / j.col(1).squaredNorm(), 1e-12);  // 8/14
}

}  // namespace
}  // namespace beamid::solver
