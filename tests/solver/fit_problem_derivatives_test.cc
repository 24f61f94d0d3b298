// Every family's fit problem (through ModelFamily::MakeProblem, as identify
// builds it) against independent checks of the program it gives Ipopt:
// the objective is ½‖weighted residuals‖², those residuals are the whitened
// misfit of the model's own sensor phasors (DisplacementPhasors) step by
// step, channel by channel, harmonic by harmonic; the gradient, the
// constraint Jacobian and the Gauss–Newton Hessian agree with central
// differences of the values in the optimiser's scaled variables, in the
// sparsity they declare; the reduced residual Jacobian agrees with
// residuals re-solved on the constraint manifold; and (harmonic balance
// with constraint curvature) the constraints' part of the Hessian agrees
// with differences of the Jacobian.
#include <cmath>
#include <memory>
#include <set>
#include <utility>

#include <gtest/gtest.h>

#include "solver/estimation/fit_data.h"
#include "solver/estimation/fit_problem.h"
#include "solver/estimation/model_family.h"
#include "tests/support/synthetic_fit_data.h"

namespace beamid::solver {
namespace {

// The problems difference parts of their own derivatives (steps ~1e-6
// relative): agreement with an independent difference of their values to
// 1e-5 of the largest entry shows the layout, the scaling and the chain
// rules are right (an error in any of those is O(1)).
constexpr double kRelativeTolerance = 1e-5;
constexpr double kStep = 1e-6;  // in the scaled variables (each ~1)

ModelStructure Structure() {
  ModelStructure structure = PolynomialModel({});
  structure.linear.push_back(LossFactor());
  return structure;
}
const std::vector<double> kParameters = {150.0, 800.0, 3e5, 0.05, 2e-4};

double WorstRelativeError(const Eigen::MatrixXd& analytic, const Eigen::MatrixXd& numeric) {
  return (analytic - numeric).cwiseAbs().maxCoeff() / numeric.cwiseAbs().maxCoeff();
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

// A sparse triplet list as a dense matrix; every entry named once.
Eigen::MatrixXd Dense(int num_rows, int num_cols, const std::vector<int>& rows, const std::vector<int>& cols,
                      const std::vector<double>& values, Eigen::MatrixXi* pattern) {
  Eigen::MatrixXd m = Eigen::MatrixXd::Zero(num_rows, num_cols);
  *pattern = Eigen::MatrixXi::Zero(num_rows, num_cols);
  for (std::size_t n = 0; n < values.size(); ++n) {
    EXPECT_EQ((*pattern)(rows[n], cols[n]), 0) << "entry (" << rows[n] << ", " << cols[n] << ") twice";
    (*pattern)(rows[n], cols[n]) = 1;
    m(rows[n], cols[n]) = values[n];
  }
  return m;
}

struct Case {
  const ModelFamily* family;
  bool constraint_curvature;
};

class FitProblemDerivatives : public ::testing::TestWithParam<Case> {
 protected:
  FitProblemDerivatives() : data_(testing::SyntheticFitData()) {
    const ModelOptions options{.num_harmonics = 5, .constraint_curvature = GetParam().constraint_curvature};
    problem_ = GetParam().family->MakeProblem(data_, Structure(), options);
    int failed = -1;
    on_manifold_ = problem_->FeasiblePoint(kParameters, &failed);
    EXPECT_EQ(failed, 0);
    // Off the constraint manifold too: the derivatives must hold everywhere.
    off_manifold_ = on_manifold_;
    for (int i = problem_->num_parameters(); i < off_manifold_.size(); ++i) off_manifold_[i] *= 1.0 + 0.03 * (i % 3);
  }

  Eigen::MatrixXd ConstraintJacobian(const Eigen::VectorXd& x, Eigen::MatrixXi* pattern) {
    const int nonzeros = problem_->JacobianNonZeros();
    std::vector<int> rows(nonzeros), cols(nonzeros);
    std::vector<double> values(nonzeros);
    problem_->JacobianStructure(rows.data(), cols.data());
    problem_->JacobianValues(x, values.data());
    return Dense(problem_->num_constraints(), problem_->num_variables(), rows, cols, values, pattern);
  }

  Eigen::MatrixXd Hessian(const Eigen::VectorXd& x, double objective_factor, const std::vector<double>& multipliers,
                          Eigen::MatrixXi* pattern) {
    const int nonzeros = problem_->HessianNonZeros();
    std::vector<int> rows(nonzeros), cols(nonzeros);
    std::vector<double> values(nonzeros);
    problem_->HessianStructure(rows.data(), cols.data());
    for (int n = 0; n < nonzeros; ++n) EXPECT_GE(rows[n], cols[n]) << "lower triangle only";
    problem_->HessianValues(x, objective_factor, multipliers.data(), values.data());
    return Dense(problem_->num_variables(), problem_->num_variables(), rows, cols, values, pattern);
  }

  FitData data_;
  std::unique_ptr<FitProblem> problem_;
  Eigen::VectorXd on_manifold_, off_manifold_;
};

TEST_P(FitProblemDerivatives, ObjectiveIsHalfTheSquaredWeightedResiduals) {
  for (const Eigen::VectorXd& x : {on_manifold_, off_manifold_}) {
    const Eigen::VectorXd r = problem_->WeightedResiduals(x);
    ASSERT_EQ(r.size(), problem_->num_residuals());
    EXPECT_NEAR(problem_->Objective(x), 0.5 * r.squaredNorm(), 1e-13 * problem_->Objective(x));
  }
}

TEST_P(FitProblemDerivatives, ResidualsAreTheWhitenedMisfitOfTheModelsSensorPhasors) {
  // Step by step, channel by channel, harmonic by harmonic (the residual
  // map reads them in this order).
  std::vector<double> positions_m;
  for (const FitChannel& c : data_.channels) positions_m.push_back(c.position_m);
  const int channels = static_cast<int>(data_.channels.size()), k_max = data_.num_fit_harmonics;
  for (const Eigen::VectorXd& x : {on_manifold_, off_manifold_}) {
    const Eigen::VectorXd r = problem_->WeightedResiduals(x);
    int n = 0;
    for (int i = 0; i < problem_->num_steps(); ++i) {
      const FitStep& s = data_.steps[i];
      const Eigen::MatrixXcd y = problem_->DisplacementPhasors(x, i, positions_m);
      for (int c = 0; c < channels; ++c)
        for (int k = 1; k <= k_max; ++k, n += 2) {
          const std::complex<double> misfit =
              DerivativeFactor(data_.channels[c].derivative_order, k * s.omega_rad_s) * y(c, k) - s.measured(c, k - 1);
          const Eigen::Vector2d expected = s.whitening[c][k - 1] * Eigen::Vector2d(misfit.real(), misfit.imag());
          EXPECT_NEAR(r[n], expected[0], 1e-9 * expected.norm() + 1e-12) << "step " << i << " channel " << c << " h" << k;
          EXPECT_NEAR(r[n + 1], expected[1], 1e-9 * expected.norm() + 1e-12) << "step " << i << " channel " << c << " h" << k;
        }
    }
    EXPECT_EQ(n, r.size());
  }
}

TEST_P(FitProblemDerivatives, GradientMatchesDifferencesOfTheObjective) {
  const Eigen::VectorXd& x = off_manifold_;
  const Eigen::MatrixXd numeric =
      Differences([&](const Eigen::VectorXd& y) { return Eigen::VectorXd::Constant(1, problem_->Objective(y)); }, x);
  Eigen::VectorXd gradient;
  problem_->Gradient(x, &gradient);
  ASSERT_EQ(gradient.size(), problem_->num_variables());
  EXPECT_LT(WorstRelativeError(gradient.transpose(), numeric), kRelativeTolerance);
}

TEST_P(FitProblemDerivatives, ConstraintJacobianMatchesDifferencesInItsSparsity) {
  for (const Eigen::VectorXd& x : {on_manifold_, off_manifold_}) {
    const Eigen::MatrixXd numeric = Differences(
        [&](const Eigen::VectorXd& y) {
          Eigen::VectorXd c;
          problem_->Constraints(y, &c);
          return c;
        },
        x);
    ASSERT_EQ(numeric.rows(), problem_->num_constraints());
    Eigen::MatrixXi pattern;
    const Eigen::MatrixXd analytic = ConstraintJacobian(x, &pattern);
    EXPECT_LT(WorstRelativeError(analytic, numeric), kRelativeTolerance);
    // Nothing outside the declared sparsity (a step's rows touch only the
    // parameters and its own state).
    const Eigen::MatrixXd outside = numeric.cwiseProduct((1 - pattern.array()).cast<double>().matrix());
    EXPECT_LT(outside.cwiseAbs().maxCoeff(), 1e-9 * numeric.cwiseAbs().maxCoeff());
  }
}

TEST_P(FitProblemDerivatives, ObjectiveHessianIsGaussNewtonOfTheResiduals) {
  const Eigen::VectorXd& x = off_manifold_;
  // Hessian(σ = 2, λ = 0) = 2·JᵀJ, J the residuals' Jacobian in scaled variables.
  const Eigen::MatrixXd jr =
      Differences([&](const Eigen::VectorXd& y) { return problem_->WeightedResiduals(y); }, x);
  Eigen::MatrixXi pattern;
  const Eigen::MatrixXd hessian = Hessian(x, 2.0, std::vector<double>(problem_->num_constraints(), 0.0), &pattern);
  const Eigen::MatrixXd expected = (2.0 * jr.transpose() * jr).triangularView<Eigen::Lower>();
  EXPECT_LT(WorstRelativeError(hessian, expected), kRelativeTolerance);
  const Eigen::MatrixXd outside = expected.cwiseProduct((1 - pattern.array()).cast<double>().matrix());
  EXPECT_LT(outside.cwiseAbs().maxCoeff(), 1e-9 * expected.cwiseAbs().maxCoeff());
}

TEST_P(FitProblemDerivatives, ConstraintCurvatureMatchesDifferencesOfTheJacobian) {
  if (!GetParam().constraint_curvature) GTEST_SKIP() << "Gauss–Newton only";
  const Eigen::VectorXd& x = off_manifold_;
  std::vector<double> multipliers(problem_->num_constraints());
  for (std::size_t i = 0; i < multipliers.size(); ++i) multipliers[i] = std::sin(1.0 + i);
  const Eigen::Map<const Eigen::VectorXd> lambda(multipliers.data(), multipliers.size());
  Eigen::MatrixXi pattern;
  const Eigen::MatrixXd numeric = Differences(
      [&](const Eigen::VectorXd& y) -> Eigen::VectorXd {
        Eigen::MatrixXi unused;
        return ConstraintJacobian(y, &unused).transpose() * lambda;
      },
      x);
  Eigen::MatrixXd expected = (0.5 * (numeric + numeric.transpose())).triangularView<Eigen::Lower>();
  Eigen::MatrixXd hessian = Hessian(x, 0.0, multipliers, &pattern);
  // The linear parameters' own block is left out by design (R is linear
  // in D and B, their curvature in the parameters is neglected).
  const int law = static_cast<int>(Structure().law_bounds.size()), p = problem_->num_parameters();
  expected.block(law, law, p - law, p - law).setZero();
  hessian.block(law, law, p - law, p - law).setZero();
  EXPECT_LT(WorstRelativeError(hessian, expected), 1e-4);
}

TEST_P(FitProblemDerivatives, ReducedResidualJacobianFollowsTheConstraints) {
  const Eigen::MatrixXd analytic = problem_->ReducedResidualJacobian(on_manifold_);
  ASSERT_EQ(analytic.rows(), problem_->num_residuals());
  ASSERT_EQ(analytic.cols(), problem_->num_parameters());
  // Re-solve every step at each nudged parameter set.
  Eigen::MatrixXd numeric(analytic.rows(), analytic.cols());
  for (int j = 0; j < problem_->num_parameters(); ++j) {
    const double h = 1e-5 * std::abs(kParameters[j]);
    std::vector<double> up = kParameters, down = kParameters;
    up[j] += h;
    down[j] -= h;
    const Eigen::VectorXd r_up = problem_->WeightedResiduals(problem_->FeasiblePoint(up));
    const Eigen::VectorXd r_down = problem_->WeightedResiduals(problem_->FeasiblePoint(down));
    numeric.col(j) = (r_up - r_down) / (2 * h);
  }
  for (int j = 0; j < problem_->num_parameters(); ++j)
    EXPECT_LT(WorstRelativeError(analytic.col(j), numeric.col(j)), 1e-4) << "parameter " << j;
}

std::string CaseName(const ::testing::TestParamInfo<Case>& info) {
  return info.param.family->Name() + (info.param.constraint_curvature ? "_curvature" : "");
}

INSTANTIATE_TEST_SUITE_P(EveryFamily, FitProblemDerivatives,
                         ::testing::Values(Case{&HarmonicBalanceFamily(), false}, Case{&HarmonicBalanceFamily(), true},
                                           Case{&MultipleScalesFamily(), false}),
                         CaseName);

}  // namespace
}  // namespace beamid::solver
