// The support's rotation and moment reconstructed from measured phasors
// through the exact linear beam: the joint cannot be measured, but at every
// step and harmonic k the sensors obey
//     Y_ck = (ikω)^d·(a_c(kω)·F_k + b_c(kω)·Θ_k),
// so Θ_k follows by weighted least squares over the channels, and the
// beam's equilibrium at its end gives the support moment
//     M_k = B(kω)·F_k − D(kω)·Θ_k.
// The static harmonic is not measured by accelerometers and is taken as 0.
// Used for the direct (linear least-squares) estimate of a law linear in its
// parameters and for the moment–rotation loops of the diagnosis.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "hb/linear_beam.h"
#include "solver/estimation/fit_data.h"

namespace beamid::solver {

struct ReconstructedStep {
  double omega_rad_s = 0.0;
  Eigen::VectorXcd theta_rad;   // Θ_0..Θ_K (Θ_0 = 0)
  Eigen::VectorXcd moment_Nm;   // M_0..M_K (M_0 = 0)
  // σ of the real and of the imaginary part of Θ_k from the channels'
  // uncertainties (1/sqrt(Σ_c |g_c|²/σ_c²)); M_k's is |D(kω)| times it.
  Eigen::VectorXd theta_std_rad;
  Eigen::VectorXcd rotational_stiffness_Nm_rad;  // D(kω), k = 0..K
};

std::vector<ReconstructedStep> ReconstructSupport(const FitData& data, const hb::LinearBeamModel& beam_model);

// Least-squares k1, k2, k3, c (k1, c ≥ 0) of M = k1·θ + k2·θ² + k3·θ³ + c·θ̇
// over the reconstructed periods of all steps.
struct DirectEstimate {
  double k1_Nm_rad = 0.0, k2_Nm_rad2 = 0.0, k3_Nm_rad3 = 0.0, c_Nms_rad = 0.0;
  double relative_residual = 0.0;  // |M − fit| / |M|
  double max_rotation_rad = 0.0;   // largest |θ(t)| reconstructed
};
DirectEstimate EstimatePolynomialDirectly(const std::vector<ReconstructedStep>& steps);

}  // namespace beamid::solver
