// The identification with the exact harmonic balance of the clamped beam
// and its support (`--model hb`): the family's step model for the stepped
// fit problem (solver/estimation/stepped_fit_problem.h), which assembles
// the program the optimiser sees.
//
// State z_i = the harmonics Θ_0..Θ_H of the support rotation at step i
// (Θ_0 real, then Re, Im of Θ_1..Θ_H: 2H + 1 unknowns).
// Balance: the harmonic-balance residual of every step, driven by that
// step's measured force phasors F_0..F_H at its estimated frequency,
//   R_i(z_i, p) = D(kω_i; p)·Θ_k + M_k(Θ; p) − B(kω_i; p)·F_k = 0,
// each harmonic's row scaled by the moment its own stiffness D(kω) takes.
// Sensor phasors: Y_ck = a_c(kω)·F_k + b_c(kω)·Θ_k (displacement).
// Derivatives are analytic in z and in the law's parameters, and difference
// quotients of the (smooth) linear part in the linear parameters. With
// ModelOptions::constraint_curvature the Hessian also has the balance's
// curvature: the analytic Jacobians differenced once more by central
// differences in the law's parameters and the states, and exactly in the
// linear parameters (R is linear in D, B).
#pragma once

#include "solver/estimation/fit_data.h"
#include "solver/estimation/model_options.h"
#include "solver/estimation/model_structure.h"
#include "solver/estimation/stepped_fit_problem.h"

namespace beamid::solver {

class IdentificationProblem : public SteppedFitProblem {
 public:
  // Throws InputError for bad options, std::invalid_argument for a
  // structure without a law or fewer model harmonics than fitted ones.
  IdentificationProblem(const FitData& data, const ModelStructure& structure, const ModelOptions& options = {});
};

}  // namespace beamid::solver
