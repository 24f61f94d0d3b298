#include "solver/estimation/nested_fit.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Cholesky>

#include "hb/option_checks.h"

namespace beamid::solver {

void NestedFitOptions::Validate() const {
  using namespace option_checks;
  model.Validate();
  RequireAtLeast("NestedFitOptions.max_iterations", max_iterations, 1);
  RequirePositive("NestedFitOptions.relative_tolerance", relative_tolerance);
}

NestedFitResult NestedFit(const FitData& data, const ModelStructure& structure, const std::vector<double>& start,
                          const NestedFitOptions& options) {
  options.Validate();
  IdentificationProblem problem(data, structure, options.model);
  const auto bounds = structure.Bounds();
  const int p = structure.NumParameters();
  NestedFitResult result;
  auto residuals = [&](const std::vector<double>& parameters) {
    result.step_solves += problem.num_steps();
    return problem.WeightedResiduals(problem.FeasiblePoint(parameters));
  };
  std::vector<double> current = start;
  Eigen::VectorXd r = residuals(current);
  double damping = 1e-3;
  for (result.iterations = 0; result.iterations < options.max_iterations; ++result.iterations) {
    Eigen::MatrixXd j(r.size(), p);
    for (int k = 0; k < p; ++k) {
      std::vector<double> nudged = current;
      const double step = 1e-6 * std::max(std::abs(current[k]), bounds[k].typical);
      nudged[k] += step;
      j.col(k) = (residuals(nudged) - r) / step;
    }
    const Eigen::MatrixXd normal = j.transpose() * j;
    const Eigen::VectorXd gradient = j.transpose() * r;
    bool improved = false;
    for (int attempt = 0; attempt < 12 && !improved; ++attempt) {
      Eigen::MatrixXd damped = normal;
      damped.diagonal() += damping * normal.diagonal();
      const Eigen::VectorXd delta = -damped.ldlt().solve(gradient);
      std::vector<double> trial = current;
      for (int k = 0; k < p; ++k) trial[k] = std::clamp(current[k] + delta[k], bounds[k].lower, bounds[k].upper);
      const Eigen::VectorXd r_trial = residuals(trial);
      if (r_trial.squaredNorm() < r.squaredNorm()) {
        const double change = (r.squaredNorm() - r_trial.squaredNorm()) / r.squaredNorm();
        double parameter_change = 0.0;
        for (int k = 0; k < p; ++k)
          parameter_change = std::max(parameter_change, std::abs(trial[k] - current[k]) /
                                                            std::max(std::abs(current[k]), bounds[k].typical));
        current = trial;
        r = r_trial;
        damping = std::max(damping * 0.3, 1e-9);
        improved = true;
        if (change < options.relative_tolerance && parameter_change < 1e3 * options.relative_tolerance) {
          result.converged = true;
          result.iterations++;
          result.parameters = current;
          result.chi_square = r.squaredNorm();
          return result;
        }
      } else {
        damping *= 10.0;
      }
    }
    if (!improved) {
      result.converged = true;  // no descent left at this precision
      break;
    }
  }
  result.parameters = current;
  result.chi_square = r.squaredNorm();
  return result;
}

}  // namespace beamid::solver
