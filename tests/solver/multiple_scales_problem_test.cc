// The multiple-scales program's derivatives against central differences of
// its own values (Ceres gradient_checker style): the constraint Jacobian and
// the objective's gradient in the optimiser's scaled variables, the
// Gauss–Newton Hessian against JᵀJ of the differenced residuals, and the
// reduced residual Jacobian (states eliminated through the constraints)
// against residuals re-solved on the constraint manifold.
#include "solver/estimation/multiple_scales_problem.h"

#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "tests/support/synthetic_fit_data.h"

namespace beamid::solver {
namespace {

using hb::Complex;

// The problem differences its own derivatives (steps 1e-6 in U, 1e-5 in the
// parameters): agreement with an independent difference of its values to
// 1e-5 of the largest entry shows the layout, the scaling and the chain
// rules are right (an error in any of those is O(1)).
constexpr double kRelativeTolerance = 1e-5;
constexpr double kStep = 1e-6;  // in the scaled variables (each ~1)

// Any data will do for derivatives.
FitData SyntheticData() { return testing::SyntheticFitData(); }

ModelStructure Structure() {
  ModelStructure structure = PolynomialModel({});
  structure.linear.push_back(LossFactor());
  return structure;
}

const std::vector<double> kParameters = {150.0, 800.0, 3e5, 0.05, 2e-4};

double WorstRelativeError(const Eigen::MatrixXd& analytic, const Eigen::MatrixXd& numeric) {
  return (analytic - numeric).cwiseAbs().maxCoeff() / numeric.cwiseAbs().maxCoeff();
}

class MultipleScalesProblemTest : public ::testing::Test {
 protected:
  MultipleScalesProblemTest() : problem_(SyntheticData(), Structure()) {
    int failed = -1;
    on_manifold_ = problem_.FeasiblePoint(kParameters, &failed);
    EXPECT_EQ(failed, 0);
    // Off the constraint manifold too: the Jacobian must hold everywhere.
    off_manifold_ = on_manifold_;
    for (int i = problem_.num_parameters(); i < off_manifold_.size(); ++i) off_manifold_[i] *= 1.0 + 0.03 * (i % 3);
  }

  // Central differences of a vector function of the scaled variables.
  template <class Function>
  Eigen::MatrixXd Differences(const Function& f, const Eigen::VectorXd& x) {
    Eigen::MatrixXd d(f(x).size(), x.size());
    for (int j = 0; j < x.size(); ++j) {
      Eigen::VectorXd up = x, down = x;
      up[j] += kStep;
      down[j] -= kStep;
      d.col(j) = (f(up) - f(down)) / (2 * kStep);
    }
    return d;
  }

  Eigen::MatrixXd ConstraintJacobian(const Eigen::VectorXd& x) {
    const int nonzeros = problem_.JacobianNonZeros();
    std::vector<int> rows(nonzeros), cols(nonzeros);
    std::vector<double> values(nonzeros);
    problem_.JacobianStructure(rows.data(), cols.data());
    problem_.JacobianValues(x, values.data());
    Eigen::MatrixXd j = Eigen::MatrixXd::Zero(problem_.num_constraints(), problem_.num_variables());
    for (int n = 0; n < nonzeros; ++n) j(rows[n], cols[n]) += values[n];
    return j;
  }

  MultipleScalesProblem problem_;
  Eigen::VectorXd on_manifold_, off_manifold_;
};

TEST_F(MultipleScalesProblemTest, ConstraintJacobianMatchesDifferences) {
  for (const Eigen::VectorXd& x : {on_manifold_, off_manifold_}) {
    const Eigen::MatrixXd numeric = Differences(
        [&](const Eigen::VectorXd& y) {
          Eigen::VectorXd c;
          problem_.Constraints(y, &c);
          return c;
        },
        x);
    const Eigen::MatrixXd analytic = ConstraintJacobian(x);
    EXPECT_LT(WorstRelativeError(analytic, numeric), kRelativeTolerance);
    // Each step's rows depend on no other step's state.
    EXPECT_LT(numeric.block(0, problem_.num_parameters() + 2, 2, 4).cwiseAbs().maxCoeff(), 1e-9);
  }
}

TEST_F(MultipleScalesProblemTest, GradientAndGaussNewtonHessianMatchDifferences) {
  const Eigen::VectorXd& x = off_manifold_;
  const Eigen::MatrixXd numeric_gradient =
      Differences([&](const Eigen::VectorXd& y) { return Eigen::VectorXd::Constant(1, problem_.Objective(y)); }, x);
  Eigen::VectorXd gradient;
  problem_.Gradient(x, &gradient);
  EXPECT_LT(WorstRelativeError(gradient.transpose(), numeric_gradient), kRelativeTolerance);

  // Hessian(σ = 2) = 2·JᵀJ, J the residuals' Jacobian in scaled variables.
  const Eigen::MatrixXd jr = Differences([&](const Eigen::VectorXd& y) { return problem_.WeightedResiduals(y); }, x);
  const int nonzeros = problem_.HessianNonZeros();
  std::vector<int> rows(nonzeros), cols(nonzeros);
  std::vector<double> values(nonzeros);
  problem_.HessianStructure(rows.data(), cols.data());
  const std::vector<double> multipliers(problem_.num_constraints(), 1.0);
  problem_.HessianValues(x, 2.0, multipliers.data(), values.data());
  Eigen::MatrixXd hessian = Eigen::MatrixXd::Zero(x.size(), x.size());
  for (int n = 0; n < nonzeros; ++n) {
    ASSERT_GE(rows[n], cols[n]) << "lower triangle only";
    hessian(rows[n], cols[n]) += values[n];
  }
  const Eigen::MatrixXd expected = 2.0 * jr.transpose() * jr;
  // Compare the lower triangles (steps do not couple through the GN Hessian).
  const Eigen::MatrixXd lower = expected.triangularView<Eigen::Lower>();
  EXPECT_LT(WorstRelativeError(hessian, lower), kRelativeTolerance);
}

TEST_F(MultipleScalesProblemTest, ReducedResidualJacobianFollowsTheConstraints) {
  const Eigen::MatrixXd analytic = problem_.ReducedResidualJacobian(on_manifold_);
  // Re-solve every step's amplitude equation at each nudged parameter set.
  Eigen::MatrixXd numeric(analytic.rows(), analytic.cols());
  for (int j = 0; j < problem_.num_parameters(); ++j) {
    const double h = 1e-5 * std::abs(kParameters[j]);
    std::vector<double> up = kParameters, down = kParameters;
    up[j] += h;
    down[j] -= h;
    const Eigen::VectorXd r_up = problem_.WeightedResiduals(problem_.FeasiblePoint(up));
    const Eigen::VectorXd r_down = problem_.WeightedResiduals(problem_.FeasiblePoint(down));
    numeric.col(j) = (r_up - r_down) / (2 * h);
  }
  for (int j = 0; j < problem_.num_parameters(); ++j)
    EXPECT_LT(WorstRelativeError(analytic.col(j), numeric.col(j)), 1e-4) << "parameter " << j;
}

TEST_F(MultipleScalesProblemTest, RefusesWhatTheModelCannotHold) {
  FitData with_masses = SyntheticData();
  with_masses.sensor_masses.point_masses.push_back({.position_m = 0.1, .mass_kg = 0.005});
  EXPECT_THROW(MultipleScalesProblem(with_masses, Structure()), std::invalid_argument);
  FitData five_harmonics = SyntheticData();
  five_harmonics.num_fit_harmonics = 5;
  EXPECT_THROW(MultipleScalesProblem(five_harmonics, Structure()), std::invalid_argument);
}

}  // namespace
}  // namespace beamid::solver
