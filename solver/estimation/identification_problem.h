// The identification as a constrained nonlinear program, independent of the
// optimiser (solver/internal/ipopt_program.* adapts it to Ipopt's TNLP).
//
// Unknowns x (scaled so that each is ~1):
//   p = support-law parameters and linear beam parameters (ModelStructure),
//   z_i = harmonics Θ_0..Θ_H of the support rotation at every step i.
// Constraints: the harmonic-balance residual of every step, driven by that
// step's measured force phasors F_0..F_H at its estimated frequency,
//   R_i(z_i, p) = D(kω_i; p)·Θ_k + M_k(Θ; p) − B(kω_i; p)·F_k = 0.
// Objective: ½ Σ_i |r_i|², r_i the whitened misfit of the fitted channels'
// harmonics 1..K (solver/fit_data.h), the model's sensor phasors being
//   Y_ck = (ikω)^d · (a_c(kω)·F_k + b_c(kω)·Θ_k).
// Derivatives are analytic in z and in the law's parameters, and difference
// quotients of the (smooth) linear part in the linear parameters.
#pragma once

#include <memory>
#include <vector>

#include <Eigen/Core>

#include "hb/harmonic_balance.h"
#include "solver/estimation/fit_data.h"
#include "solver/estimation/fit_problem.h"
#include "solver/estimation/model_options.h"
#include "solver/estimation/model_structure.h"
#include "solver/estimation/parameter_scaling.h"
#include "solver/estimation/support_reconstruction.h"

namespace beamid::solver {

class IdentificationProblem : public FitProblem {
 public:
  IdentificationProblem(const FitData& data, const ModelStructure& structure,
                        const ModelOptions& options = {});
  ~IdentificationProblem();
  IdentificationProblem(const IdentificationProblem&) = delete;
  IdentificationProblem& operator=(const IdentificationProblem&) = delete;

  int num_parameters() const override { return num_parameters_; }
  int num_steps() const override { return static_cast<int>(data_.steps.size()); }
  int state_size() const { return state_size_; }
  int num_variables() const override { return num_parameters_ + num_steps() * state_size_; }
  int num_constraints() const override { return num_steps() * state_size_; }
  int num_residuals() const override { return data_.NumResiduals(); }
  const FitData& data() const { return data_; }
  const ModelStructure& structure() const override { return structure_; }
  int num_model_harmonics() const override { return options_.num_harmonics; }

  // Scaled ↔ physical.
  std::vector<double> Parameters(const Eigen::VectorXd& x) const override;
  Eigen::VectorXd States(const Eigen::VectorXd& x, int step) const;  // z_i, physical
  // x with these parameters and, per step, the harmonic-balance solution
  // driven by the measured force (warm-started along each sweep). Steps where
  // Newton fails keep the linear response; the count is returned.
  Eigen::VectorXd FeasiblePoint(const std::vector<double>& parameters, int* failed_steps = nullptr) override;
  Eigen::VectorXd MeasuredStatePoint(const std::vector<double>& parameters) override;
  void Bounds(Eigen::VectorXd* lower, Eigen::VectorXd* upper) const override;

  double Objective(const Eigen::VectorXd& x) override;
  void Gradient(const Eigen::VectorXd& x, Eigen::VectorXd* gradient) override;
  void Constraints(const Eigen::VectorXd& x, Eigen::VectorXd* constraints) override;
  // Fixed sparsity: step i's rows touch all parameters and its own z_i.
  int JacobianNonZeros() const override { return num_constraints() * (num_parameters_ + state_size_); }
  void JacobianStructure(int* rows, int* cols) const override;
  void JacobianValues(const Eigen::VectorXd& x, double* values) override;

  // Hessian of the Lagrangian, lower triangle. The objective's part is
  // Gauss–Newton (exact in z: the residual is linear in the states); the
  // constraints' part, if asked for, differentiates the analytic Jacobians
  // once more by central differences in the law's parameters and the
  // states, and exactly in the linear parameters (R is linear in D, B).
  int HessianNonZeros() const override;
  void HessianStructure(int* rows, int* cols) const override;
  void HessianValues(const Eigen::VectorXd& x, double objective_factor, const double* multipliers,
                     double* values) override;

  // Whitened residuals r (all steps), and their Jacobian in the reduced
  // space (states eliminated through the constraints), physical units.
  Eigen::VectorXd WeightedResiduals(const Eigen::VectorXd& x) override;
  Eigen::MatrixXd ReducedResidualJacobian(const Eigen::VectorXd& x) override;

  // Model phasors of harmonics 0..H at positions for step i (displacement,
  // m), with the parameters and states of x.
  Eigen::MatrixXcd DisplacementPhasors(const Eigen::VectorXd& x, int step,
                                       const std::vector<double>& positions_m) override;
  Eigen::VectorXcd StepState(const Eigen::VectorXd& x, int step) const override {
    return hb::HarmonicBalance::ToComplex(States(x, step));
  }

 private:
  struct StepCache;
  void Evaluate(const Eigen::VectorXd& x);
  // The support rotation the measurements show through the exact linear beam
  // with these linear parameters (solver/support_reconstruction.h; empty
  // when too few channels reconstruct it).
  std::vector<ReconstructedStep> MeasuredRotations(const std::vector<double>& parameters) const;
  // FeasiblePoint with Newton started at `measured` where it is given.
  Eigen::VectorXd FeasiblePointFrom(const std::vector<double>& parameters,
                                    const std::vector<ReconstructedStep>& measured, int* failed_steps);
  void UpdateLinear(const std::vector<double>& linear_values);
  Eigen::VectorXd ModelResidual(int step, const Eigen::VectorXd& z, const hb::LinearHarmonics& linear) const;

  FitData data_;
  ModelStructure structure_;
  ModelOptions options_;
  int num_law_ = 0, num_linear_ = 0, num_parameters_ = 0, state_size_ = 0;
  ParameterScaling scaling_;  // of the parameters, the first entries of x
  // Per step: the scale of its states (its rotation's size) and of its
  // constraints (the moment that rotation takes), so every variable and
  // every equation the optimiser sees is ~1 at every amplitude.
  std::vector<double> theta_scale_rad_;
  std::vector<Eigen::VectorXd> constraint_scale_Nm_;  // per step, per row (harmonic)
  std::vector<double> positions_m_;
  hb::LinearBeamModel base_model_;
  std::unique_ptr<hb::HarmonicBalance> balance_;

  // Linear part per step at the current linear parameters, and at each
  // parameter nudged for the difference quotients.
  std::vector<double> linear_values_;
  bool linear_valid_ = false;
  std::vector<hb::LinearHarmonics> linear_;
  std::vector<std::vector<hb::LinearHarmonics>> linear_nudged_;  // [parameter][step]
  std::vector<double> linear_step_;

  Eigen::VectorXd cached_x_;
  std::vector<StepCache> cache_;
  double objective_ = 0.0;
};

}  // namespace beamid::solver
