// The identification with the seed's multiple-scales model (`--model ms`,
// hb/multiple_scales.h, docs/derivation.md) as a constrained nonlinear
// program, independent of the optimiser.
//
// Unknowns x (scaled so that each is ~1):
//   p = k1, k2, k3, c of the polynomial law and the linear beam parameters
//       (ModelStructure),
//   U_i = the complex modal phasor of the first mode at every step i
//         (Re U_i, Im U_i).
// Constraints: the solvability condition (corrected Eq. 40) of every step,
// driven by that step's measured force fundamental F1 at its frequency Ω_i,
//   S_i(U_i, p) = m_eff·(ω0² − Ω_i²)·U_i − F1·w(x_F) + w'(L)·M1(U_i, Ω_i) = 0.
// Objective: ½ Σ_i |r_i|², r_i the whitened misfit (solver/fit_data.h) of the
// fitted channels' harmonics 1..K (K ≤ 3), the model's sensor phasors being
//   Y_ck = (ikΩ)^d · h_k(x_c; U_i, Ω_i, F1)
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
// change of the states alone costs only polynomials in U. The Hessian is the objective's Gauss–Newton JᵀJ
// alone (the constrained Gauss–Newton method, as IdentificationProblem with
// constraint_curvature = false).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "hb/multiple_scales.h"
#include "solver/estimation/fit_data.h"
#include "solver/estimation/fit_problem.h"
#include "solver/estimation/model_structure.h"
#include "solver/estimation/parameter_scaling.h"

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

class MultipleScalesProblem : public FitProblem {
 public:
  // Throws std::invalid_argument if the law is not the polynomial one, more
  // than 3 harmonics are fitted, or the campaign's beam has attachments the
  // model cannot hold (sensor masses).
  MultipleScalesProblem(const FitData& data, const ModelStructure& structure,
                        const MultipleScalesProblemOptions& options = {});
  ~MultipleScalesProblem();
  MultipleScalesProblem(const MultipleScalesProblem&) = delete;
  MultipleScalesProblem& operator=(const MultipleScalesProblem&) = delete;

  static constexpr int kStateSize = 2;  // Re U, Im U

  int num_parameters() const override { return num_parameters_; }
  int num_steps() const override { return static_cast<int>(data_.steps.size()); }
  int num_variables() const override { return num_parameters_ + kStateSize * num_steps(); }
  int num_constraints() const override { return kStateSize * num_steps(); }
  int num_residuals() const override { return data_.NumResiduals(); }
  const FitData& data() const { return data_; }
  const ModelStructure& structure() const override { return structure_; }
  int num_model_harmonics() const override { return 3; }

  // Scaled ↔ physical.
  std::vector<double> Parameters(const Eigen::VectorXd& x) const override;
  hb::Complex ModalPhasor_m(const Eigen::VectorXd& x, int step) const;  // U_i
  // The multiple-scales model with these physical parameters.
  hb::MultipleScalesModel Model(const std::vector<double>& parameters) const;

  // x with these parameters and, per step, a root of the amplitude equation
  // (MultipleScalesModel::Solve). Where there are three, the middle one is
  // unstable and never taken; of the two outer ones the step takes the one
  // whose sensor phasors are closer (whitened) to the measured ones: the
  // data tell which branch the test was on, while the model's own sweep
  // history would put the jump where the start's parameters put it. Steps
  // where the model has no solution (an internal resonance) keep U = 0 and
  // are counted.
  Eigen::VectorXd FeasiblePoint(const std::vector<double>& parameters, int* failed_steps = nullptr) override;
  void Bounds(Eigen::VectorXd* lower, Eigen::VectorXd* upper) const override;

  double Objective(const Eigen::VectorXd& x) override;
  void Gradient(const Eigen::VectorXd& x, Eigen::VectorXd* gradient) override;
  void Constraints(const Eigen::VectorXd& x, Eigen::VectorXd* constraints) override;
  // Step i's two rows touch all parameters and its own U_i.
  int JacobianNonZeros() const override { return num_constraints() * (num_parameters_ + kStateSize); }
  void JacobianStructure(int* rows, int* cols) const override;
  void JacobianValues(const Eigen::VectorXd& x, double* values) override;
  // Gauss–Newton of the objective: the parameter block and, per step, U_i's
  // rows against the parameters and itself.
  int HessianNonZeros() const override;
  void HessianStructure(int* rows, int* cols) const override;
  void HessianValues(const Eigen::VectorXd& x, double objective_factor, const double* multipliers,
                     double* values) override;

  Eigen::VectorXd WeightedResiduals(const Eigen::VectorXd& x) override;
  // dr/dp along the constraints: dU/dp = −(∂S/∂U)⁻¹·∂S/∂p per step.
  Eigen::MatrixXd ReducedResidualJacobian(const Eigen::VectorXd& x) override;

  // Model phasors of harmonics 0..3 at positions for step i (displacement,
  // m), with the parameters and states of x.
  Eigen::MatrixXcd DisplacementPhasors(const Eigen::VectorXd& x, int step,
                                       const std::vector<double>& positions_m) override;
  Eigen::VectorXcd StepState(const Eigen::VectorXd& x, int step) const override {
    return Eigen::VectorXcd::Constant(1, ModalPhasor_m(x, step));
  }

 private:
  struct StepCache;
  struct ModelSet;
  void Evaluate(const Eigen::VectorXd& x);
  const ModelSet& ModelsAt(const std::vector<double>& parameters);
  // Whitened misfit r_i and solvability residual S_i of step i with U, from
  // the model's excitation at that step.
  Eigen::VectorXd StepResidual(const hb::MultipleScalesModel::Excitation& excitation, int step, hb::Complex u) const;
  static Eigen::Vector2d StepConstraint(const hb::MultipleScalesModel::Excitation& excitation, hb::Complex u);

  FitData data_;
  ModelStructure structure_;
  MultipleScalesProblemOptions options_;
  int num_parameters_ = 0;
  ParameterScaling scaling_;  // of the parameters, the first entries of x
  hb::BeamProperties base_beam_;
  // Per step: the scale of U_i (its size) and of S_i (the force that size
  // takes, |∂S/∂U|·|U|), so variables and equations are ~1 at every level.
  std::vector<double> state_scale_m_;
  std::vector<double> constraint_scale_N_;

  std::unique_ptr<ModelSet> models_;
  Eigen::VectorXd cached_x_;
  std::vector<StepCache> cache_;
  double objective_ = 0.0;
};

}  // namespace beamid::solver
