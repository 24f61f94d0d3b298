#include "solver/estimation/parameter_covariance.h"

#include <Eigen/Eigenvalues>

namespace beamid::solver {

ParameterCovariance SandwichCovariance(const Eigen::MatrixXd& whitened_jacobian,
                                       const Eigen::MatrixXd& shared_information,
                                       const Eigen::MatrixXd& model_error_information, double variance_scale) {
  const Eigen::MatrixXd information = whitened_jacobian.transpose() * whitened_jacobian;
  const Eigen::VectorXd scale = information.diagonal().cwiseSqrt().cwiseMax(1e-300);
  const auto unscaled = scale.cwiseInverse().asDiagonal();
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> normalised(unscaled * information * unscaled);
  const Eigen::VectorXd values = normalised.eigenvalues().cwiseMax(1e-300);
  const Eigen::MatrixXd inverse =
      normalised.eigenvectors() * values.cwiseInverse().asDiagonal() * normalised.eigenvectors().transpose();
  const Eigen::MatrixXd shared = unscaled * shared_information * unscaled;
  const Eigen::MatrixXd model_error = unscaled * model_error_information * unscaled;
  ParameterCovariance out;
  out.model_error = unscaled * inverse * model_error * inverse * unscaled;
  out.total = variance_scale * unscaled * (inverse + inverse * shared * inverse) * unscaled + out.model_error;
  out.collinear = normalised.eigenvalues().minCoeff() < 1e-8 * normalised.eigenvalues().maxCoeff();
  return out;
}

}  // namespace beamid::solver
