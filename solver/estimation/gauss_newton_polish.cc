#include "solver/estimation/gauss_newton_polish.h"

#include <algorithm>
#include <cmath>
#include <cstddef>

#include <Eigen/QR>

namespace beamid::solver {

Eigen::VectorXd BoundedGaussNewtonStep(const Eigen::MatrixXd& jacobian, const Eigen::VectorXd& residuals,
                                       const std::vector<double>& p, const std::vector<ParameterBounds>& bounds) {
  const Eigen::Index n = jacobian.cols();
  std::vector<std::optional<double>> held(static_cast<std::size_t>(n));  // the bound it is held at
  Eigen::VectorXd dp = Eigen::VectorXd::Zero(n);
  for (Eigen::Index round = 0; round <= n; ++round) {
    Eigen::MatrixXd free = jacobian;
    Eigen::VectorXd rest = residuals;
    for (Eigen::Index k = 0; k < n; ++k)
      if (const auto& bound = held[static_cast<std::size_t>(k)]) {
        rest += jacobian.col(k) * (*bound - p[static_cast<std::size_t>(k)]);
        free.col(k).setZero();
      }
    // Columns of unit norm: the parameters' units differ by many decades.
    const Eigen::VectorXd norms =
        free.colwise().norm().transpose().unaryExpr([](double v) { return v > 0.0 ? v : 1.0; });
    dp = (free * norms.cwiseInverse().asDiagonal()).completeOrthogonalDecomposition().solve(-rest).cwiseQuotient(norms);
    bool changed = false;
    for (Eigen::Index k = 0; k < n; ++k) {
      const std::size_t i = static_cast<std::size_t>(k);
      if (held[i]) {
        dp[k] = *held[i] - p[i];
      } else if (p[i] + dp[k] < bounds[i].lower || p[i] + dp[k] > bounds[i].upper) {
        held[i] = p[i] + dp[k] < bounds[i].lower ? bounds[i].lower : bounds[i].upper;
        changed = true;
      }
    }
    if (!changed) break;
  }
  return dp;
}

std::optional<PolishedPoint> PolishInReducedSpace(FitProblem& problem, const std::vector<double>& start) {
  const std::vector<ParameterBounds> bounds = problem.structure().Bounds();
  // Every evaluation follows its own FeasiblePoint, which sets the problem's
  // scales at those parameters.
  const auto solve = [&](const std::vector<double>& at, Eigen::VectorXd* x) {
    int failed_steps = 0;
    *x = problem.FeasiblePoint(at, &failed_steps);
    return failed_steps == 0;
  };
  std::vector<double> p = start;
  for (int step = 0; step < kPolishSteps; ++step) {
    Eigen::VectorXd x;
    if (!solve(p, &x)) return std::nullopt;
    const Eigen::VectorXd r = problem.WeightedResiduals(x);
    const Eigen::MatrixXd j = problem.ReducedResidualJacobian(x);
    const double chi_square = r.squaredNorm();
    const double misfit_scale =
        std::max(1.0, chi_square / std::max(1, problem.num_residuals() - static_cast<int>(j.cols())));
    const Eigen::VectorXd dp = BoundedGaussNewtonStep(j, r, p, bounds);
    const double decrement = chi_square - (r + j * dp).squaredNorm();
    if (!std::isfinite(decrement)) return std::nullopt;
    if (decrement <= kStationaryDecrement * misfit_scale)
      return PolishedPoint{.parameters = p, .x = x, .chi_square = chi_square, .decrement = decrement};
    bool moved = false;
    for (double t = 1.0; !moved && t >= 1.0 / 16.0; t *= 0.5) {
      std::vector<double> trial = p;
      for (std::size_t k = 0; k < trial.size(); ++k)
        trial[k] = std::clamp(p[k] + t * dp[static_cast<Eigen::Index>(k)], bounds[k].lower, bounds[k].upper);
      Eigen::VectorXd x_trial;
      if (solve(trial, &x_trial) && problem.WeightedResiduals(x_trial).squaredNorm() < chi_square) {
        p = trial;
        moved = true;
      }
    }
    if (!moved) return std::nullopt;
  }
  return std::nullopt;
}

}  // namespace beamid::solver
