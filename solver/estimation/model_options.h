// What every model family (solver/estimation/model_family.h) is told about
// the model to build: how many harmonics it carries, how the harmonic
// balance samples a period, whether the optimiser sees the constraints'
// curvature, and the beam's known loss factor. A family uses the fields
// that mean something to it (multiple scales: only the loss factor; its
// harmonics are 0..3 whatever num_harmonics says).
#pragma once

namespace beamid::solver {

struct ModelOptions {
  int num_harmonics = 5;  // H of the model (≥ K + 2 keeps harmonics 1..K accurate)
  int num_time_samples = 0;  // 0: HarmonicBalanceOptions' automatic choice
  // The Hessian's constraint curvature Σλ·∂²R (by differences of the
  // analytic Jacobians). Off: the constrained Gauss–Newton method (Bock),
  // whose Hessian is the objective's JᵀJ alone — measured 4× cheaper per
  // iteration and as fast to converge on the paper's campaigns, since the
  // multipliers are small when the fit is good.
  bool constraint_curvature = false;
  // The beam's structural loss factor η when it is known (a separate test of
  // the beam); campaign.json has none. Steel: ~1e-4.
  double beam_loss_factor = 0.0;

  // Throws InputError naming the field, its value and the allowed range.
  void Validate() const;
};

}  // namespace beamid::solver
