#include "solver/estimation/model_phasors.h"

#include <stdexcept>
#include <string>

namespace beamid::solver {

std::vector<Eigen::MatrixXcd> ModelPhasors(const FitData& data, FitProblem& problem,
                                           const Eigen::VectorXd& x) {
  if (static_cast<int>(data.steps.size()) != problem.num_steps()) {
    throw std::invalid_argument("ModelPhasors: the data have " + std::to_string(data.steps.size()) +
                                " steps, the fitted problem " + std::to_string(problem.num_steps()));
  }
  std::vector<double> positions;
  for (const auto& c : data.channels) positions.push_back(c.position_m);
  std::vector<Eigen::MatrixXcd> out;
  for (int i = 0; i < static_cast<int>(data.steps.size()); ++i) {
    const Eigen::MatrixXcd y = problem.DisplacementPhasors(x, i, positions);
    Eigen::MatrixXcd m = Eigen::MatrixXcd::Zero(data.channels.size(), data.num_fit_harmonics);
    for (std::size_t c = 0; c < data.channels.size(); ++c) {
      for (int k = 1; k <= data.num_fit_harmonics && k < y.cols(); ++k)
        m(c, k - 1) = DerivativeFactor(data.channels[c].derivative_order, k * data.steps[i].omega_rad_s) * y(c, k);
    }
    out.push_back(std::move(m));
  }
  return out;
}

}  // namespace beamid::solver
