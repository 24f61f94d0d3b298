// Errors every phasor of a step shares: the force's amplitude (the model is
// driven with it), its phase (every response is referred to it) and the
// frequency read from the record (the model is evaluated at it). Each
// phasor's covariance holds its own share of them (phasor_uncertainty.h), so
// every phasor is weighed right; but the fit whitens phasor by phasor and
// so counts them as independent, while across a step's channels and
// harmonics they are one error each and do not average out. The parameters'
// covariance is therefore the sandwich
//     Cov(p) = A⁻¹·B·A⁻¹,   A = JᵀJ,   B = Jᵀ·Σ·J = A + Σ_s,m (T_sm·T_smᵀ − Σ_i t_smi·t_smiᵀ),
// J the whitened residuals' Jacobian, Σ their covariance, t_smi = J_iᵀ·L_i⁻¹·v_smi
// for phasor i of step s (its two rows J_i, its whitening L_i⁻¹) and v_smi
// the change of that phasor for a one-σ error of source m
// (FitStep::shared_errors), T_sm = Σ_i t_smi. Only the blocks between
// different phasors are added: each phasor's own block is in A already.
#pragma once

#include <Eigen/Core>

#include "solver/estimation/fit_data.h"

namespace beamid::solver {

// B − A of the sandwich above, for `whitened_jacobian` with the rows of
// FitData::NumResiduals (step by step, channel by channel, harmonic by
// harmonic, real then imaginary part). Zero when no step has shared errors.
Eigen::MatrixXd SharedErrorInformation(const FitData& data, const Eigen::MatrixXd& whitened_jacobian);

}  // namespace beamid::solver
