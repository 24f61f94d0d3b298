#include "solver/estimation/shared_step_errors.h"

#include <stdexcept>

namespace beamid::solver {

Eigen::MatrixXd SharedErrorInformation(const FitData& data, const Eigen::MatrixXd& whitened_jacobian) {
  const Eigen::Index num_parameters = whitened_jacobian.cols();
  if (whitened_jacobian.rows() != data.NumResiduals())
    throw std::invalid_argument("SharedErrorInformation: the Jacobian's rows are not the data's residuals");
  const int channels = static_cast<int>(data.channels.size());
  const int k_max = data.num_fit_harmonics;
  const Eigen::Index rows_per_step = 2 * channels * k_max;
  Eigen::MatrixXd extra = Eigen::MatrixXd::Zero(num_parameters, num_parameters);
  for (std::size_t s = 0; s < data.steps.size(); ++s) {
    const FitStep& step = data.steps[s];
    const Eigen::Index offset = static_cast<Eigen::Index>(s) * rows_per_step;
    for (const Eigen::MatrixXcd& source : step.shared_errors) {
      Eigen::VectorXd total = Eigen::VectorXd::Zero(num_parameters);
      for (int c = 0; c < channels; ++c)
        for (int k = 1; k <= k_max; ++k) {
          const std::complex<double> v = source(c, k - 1);
          const Eigen::Vector2d whitened = step.whitening[c][k - 1] * Eigen::Vector2d(v.real(), v.imag());
          const Eigen::VectorXd t =
              whitened_jacobian.middleRows<2>(offset + 2 * (c * k_max + k - 1)).transpose() * whitened;
          total += t;
          extra -= t * t.transpose();
        }
      extra += total * total.transpose();
    }
  }
  return extra;
}

}  // namespace beamid::solver
