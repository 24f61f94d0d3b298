// The identification with the seed's multiple-scales model (`--model ms`,
// hb/multiple_scales.h, docs/derivation.md): the family's step model for
// the stepped fit problem (solver/estimation/stepped_fit_problem.h), which
// assembles the program the optimiser sees.
//
// Parameters: k1, k2, k3, c of the polynomial law and the linear beam
// parameters (ModelStructure).
// State U_i = the complex modal phasor of the first mode at step i
// (Re U_i, Im U_i).
// Balance: the solvability condition (corrected Eq. 40) of every step,
// driven by that step's measured force fundamental F1 at its frequency Ω_i,
//   S_i(U_i, p) = m_eff·(ω0² − Ω_i²)·U_i − F1·w(x_F) + w'(L)·M1(U_i, Ω_i) = 0,
// scaled by the force U_i's size takes (|∂S/∂U|·|U|).
// Sensor phasors (fitted harmonics 1..K, K ≤ 3):
//   Y_ck = h_k(x_c; U_i, Ω_i, F1)
// with h1..h3 the displacement harmonics of MultipleScalesModel::Response
// (the shapes w, Q(λ√2), Q(λ√3) and N of the seed).
//
// The model's linear part is a plain beam: it has no point masses, clamp
// compliance or lateral support spring, so a campaign with sensor masses is
// refused (use the harmonic-balance model). Higher force harmonics do not
// enter (outside the ordering).
//
// Derivatives: by central differences everywhere — in (Re U, Im U) with a
// step of 1e-6·|U| (S and h_k are cubic polynomials in U and Ū, so the
// error is ~1e-12 relative), and in the parameters with a step of
// 1e-5·max(|p|, typical), one-sided second-order at a bound the model
// refuses to cross (k1 ≥ 0, c ≥ 0). The model is rebuilt for every nudged
// parameter set, and of each its U-independent part at every step
// (MultipleScalesModel::Excitation: the receptances at Ω, 2Ω, 3Ω and the
// sensors); that set is kept while the parameters do not change, so a
// change of the states alone costs only polynomials in U. The Hessian is the
// objective's Gauss–Newton JᵀJ alone (the constrained Gauss–Newton method,
// as IdentificationProblem with constraint_curvature = false).
//
// The feasible point takes per step a root of the amplitude equation
// (MultipleScalesModel::Solve). Where there are three, the middle one is
// unstable and never taken; of the two outer ones the step takes the one
// whose sensor phasors are closer (whitened) to the measured ones: the data
// tell which branch the test was on, while the model's own sweep history
// would put the jump where the start's parameters put it. Steps where the
// model has no solution (an internal resonance) keep U = 0 and are counted.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "hb/multiple_scales.h"
#include "solver/estimation/fit_data.h"
#include "solver/estimation/model_structure.h"
#include "solver/estimation/stepped_fit_problem.h"

namespace beamid::solver {

struct MultipleScalesProblemOptions {
  // The beam's structural loss factor η when it is known (campaign.json has
  // none); a "loss_factor" linear parameter overrides it.
  double beam_loss_factor = 0.0;
  // kExcitation (default): the generalised model, exact in the linear limit;
  // kNatural: the seed's strict first-order form.
  hb::MultipleScalesOptions model;

  // Throws InputError naming the field, its value and the allowed range.
  void Validate() const;
};

// The multiple-scales model of the plain `beam` with the polynomial law and
// linear parameters of `structure` set to `parameters` (structure order).
// Throws std::invalid_argument for another law or a linear parameter that
// adds attachments (point masses, a compliant clamp).
hb::MultipleScalesModel MakeMultipleScalesModel(const hb::BeamProperties& beam, double force_position_m,
                                                const ModelStructure& structure, const std::vector<double>& parameters,
                                                const hb::MultipleScalesOptions& options = {});

class MultipleScalesProblem : public SteppedFitProblem {
 public:
  // Throws std::invalid_argument if the law is not the polynomial one, more
  // than 3 harmonics are fitted, or the campaign's beam has attachments the
  // model cannot hold (sensor masses).
  MultipleScalesProblem(const FitData& data, const ModelStructure& structure,
                        const MultipleScalesProblemOptions& options = {});
};

}  // namespace beamid::solver
