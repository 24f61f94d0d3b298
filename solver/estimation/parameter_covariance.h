// The covariance of a weighted least-squares fit's parameters, linearised
// at its optimum:
//     Cov = s·A⁻¹·(A + S)·A⁻¹ + A⁻¹·M·A⁻¹,   A = JᵀJ,
// J the whitened residuals' Jacobian, S what the errors a step's phasors
// share add to the information a phasor-by-phasor whitening counts
// (shared_step_errors.h), M what the residual model error adds
// (model_error.h), and s the variance scale: max(1, reduced χ²) where no
// model error is estimated (the relative floor's σ are no noise model),
// else 1. A is inverted scale-free (unit diagonal): in physical units its
// diagonal spans 20 orders of magnitude (k3 in N·m/rad³ beside a clamp
// compliance in rad/(N·m)), beyond double precision, and rounding made
// eigenvalues of well-determined directions negative (intervals of ±1e143).
#pragma once

#include <Eigen/Core>

namespace beamid::solver {

struct ParameterCovariance {
  Eigen::MatrixXd total;
  Eigen::MatrixXd model_error;  // A⁻¹·M·A⁻¹, the part the residual model error makes
  // The scale-free information's smallest eigenvalue is below 1e-8 of its
  // largest: some combination of the parameters is not identifiable.
  bool collinear = false;
};

ParameterCovariance SandwichCovariance(const Eigen::MatrixXd& whitened_jacobian,
                                       const Eigen::MatrixXd& shared_information,
                                       const Eigen::MatrixXd& model_error_information, double variance_scale);

}  // namespace beamid::solver
