// The fit problem of a stepped-sine campaign, written once for every model
// family: what the optimiser sees (fit_problem.h) assembled from what a
// family knows of one step (StepModel).
//
// Unknowns x (scaled so that each is ~1):
//   p   = the structure's parameters, each by its typical size
//         (parameter_scaling.h),
//   z_i = the state of step i (m real unknowns: the family's), by the
//         state's size at that step (set by FeasiblePoint).
// Constraints: the family's balance at every step, R_i(z_i, p) = 0, each
// row by the size of what the state's size takes there (the family's
// BalanceScale), so that every equation is ~1 at every amplitude.
// Objective: ½ Σ_i |r_i|², r_i the whitened misfit (solver/fit_data.h) of
// the fitted channels' harmonics 1..K, channel by channel, harmonic by
// harmonic, of the family's sensor phasors Y (displacement):
//   r_ick = W_ick · [Re; Im]((ikω_i)^d_c · Y_ick − measured_ick).
// The Hessian is the objective's Gauss–Newton JᵀJ plus, where the family
// gives it, the curvature of the balance Σ λ·∂²R. The covariance's inputs
// (the weighted residuals and their Jacobian with the states eliminated
// through the balance) come from the same per-step derivatives.
#pragma once

#include <functional>
#include <memory>
#include <vector>

#include <Eigen/Core>

#include "solver/estimation/fit_data.h"
#include "solver/estimation/fit_problem.h"
#include "solver/estimation/model_structure.h"
#include "solver/estimation/parameter_scaling.h"

namespace beamid::solver {

// What a model family knows of one step of the campaign, in physical units:
// its state, its balance equations there and its predicted sensor phasors,
// with their derivatives in the state and in the parameters.
class StepModel {
 public:
  virtual ~StepModel() = default;

  // Real unknowns of a step's state (m), and the size a state has before
  // any is solved for (the states' scale until SolveStates).
  virtual int state_size() const = 0;
  virtual double TypicalStateSize() const = 0;
  // The highest harmonic the model gives (H).
  virtual int num_model_harmonics() const = 0;

  // The physical parameters (structure order) that what follows is at; the
  // model keeps what depends on them alone while they do not change.
  virtual void SetParameters(const std::vector<double>& parameters) = 0;

  struct Values {
    Eigen::VectorXd balance;                // R_i (m)
    Eigen::MatrixXd balance_d_state;        // ∂R_i/∂z (m × m)
    Eigen::MatrixXd balance_d_parameters;   // ∂R_i/∂p (m × P)
    Eigen::VectorXcd sensors;               // Y at the fitted channels, entry c·K + k − 1 [m]
    Eigen::MatrixXcd sensors_d_state;       // ∂Y/∂z (C·K × m)
    Eigen::MatrixXcd sensors_d_parameters;  // ∂Y/∂p (C·K × P)
  };
  // Step i with state z at the parameters set; state_scale is the size of
  // the step's states (for difference quotients in z).
  virtual void Evaluate(int step, const Eigen::VectorXd& z, double state_scale, Values* values) = 0;
  // The second derivatives of μᵀR_i w.r.t. (p, z) ((P + m) square) at the
  // parameters set, or false where the family leaves the Hessian to the
  // objective's Gauss–Newton part.
  virtual bool BalanceCurvature(int /*step*/, const Eigen::VectorXd& /*z*/, double /*state_scale*/,
                                const Eigen::VectorXd& /*mu*/, Eigen::MatrixXd* /*second*/) {
    return false;
  }

  // Per step, a state that satisfies the balance with these parameters as
  // well as the model allows (and the count of steps where that failed);
  // in *measured (when asked for, and the family can tell) the states the
  // measurements show instead, on the measured branch whatever the
  // parameters. Leaves the parameters set.
  virtual std::vector<Eigen::VectorXd> SolveStates(const std::vector<double>& parameters, int* failed_steps,
                                                   std::vector<Eigen::VectorXd>* measured) = 0;
  // The size of each row of R_i at a state of this size (the scale of the
  // constraints), at the parameters set.
  virtual Eigen::VectorXd BalanceScale(int step, const Eigen::VectorXd& z, double state_scale) = 0;

  // What a report and `beamid predict` need: displacement phasors of
  // harmonics 0..H at positions for step i (positions × (H + 1)), and the
  // state as complex phasors in physical units (ModelFamily::StateName).
  virtual Eigen::MatrixXcd DisplacementPhasors(const std::vector<double>& parameters, int step,
                                               const Eigen::VectorXd& z, const std::vector<double>& positions_m) = 0;
  virtual Eigen::VectorXcd StepState(const Eigen::VectorXd& z) const = 0;
};

// The whitened misfit r_i of sensor phasors Y at step i (layout above), and
// the same map applied to derivatives of Y (its linear part).
Eigen::VectorXd WhitenedMisfit(const FitData& data, int step, const Eigen::VectorXcd& sensors);
Eigen::MatrixXd WhitenedDerivative(const FitData& data, int step, const Eigen::MatrixXcd& sensors_derivative);

class SteppedFitProblem : public FitProblem {
 public:
  // The family's model of one step, made for the problem's own copies of
  // the data and the structure (which outlive it).
  using StepModelFactory = std::function<std::unique_ptr<StepModel>(const FitData&, const ModelStructure&)>;
  SteppedFitProblem(const FitData& data, const ModelStructure& structure, const StepModelFactory& make_model);
  ~SteppedFitProblem() override;
  SteppedFitProblem(const SteppedFitProblem&) = delete;
  SteppedFitProblem& operator=(const SteppedFitProblem&) = delete;

  int num_parameters() const override { return scaling_.size(); }
  int num_steps() const override { return static_cast<int>(data_.steps.size()); }
  int state_size() const { return state_size_; }
  int num_variables() const override { return num_parameters() + num_steps() * state_size_; }
  int num_constraints() const override { return num_steps() * state_size_; }
  int num_residuals() const override { return data_.NumResiduals(); }
  const FitData& data() const { return data_; }
  const ModelStructure& structure() const override { return structure_; }
  int num_model_harmonics() const override { return model_->num_model_harmonics(); }

  // Scaled ↔ physical.
  std::vector<double> Parameters(const Eigen::VectorXd& x) const override;
  Eigen::VectorXd States(const Eigen::VectorXd& x, int step) const;  // z_i, physical
  // Also sets the states' and the constraints' scales from the states found.
  Eigen::VectorXd FeasiblePoint(const std::vector<double>& parameters, int* failed_steps = nullptr) override;
  Eigen::VectorXd MeasuredStatePoint(const std::vector<double>& parameters) override;
  void Bounds(Eigen::VectorXd* lower, Eigen::VectorXd* upper) const override;

  double Objective(const Eigen::VectorXd& x) override;
  void Gradient(const Eigen::VectorXd& x, Eigen::VectorXd* gradient) override;
  void Constraints(const Eigen::VectorXd& x, Eigen::VectorXd* constraints) override;
  // Fixed sparsity: step i's rows touch all parameters and its own z_i.
  int JacobianNonZeros() const override { return num_constraints() * (num_parameters() + state_size_); }
  void JacobianStructure(int* rows, int* cols) const override;
  void JacobianValues(const Eigen::VectorXd& x, double* values) override;
  // Lower triangle: the parameter block row by row, then per step and per
  // state row its P parameter entries and its own states up to the diagonal.
  int HessianNonZeros() const override;
  void HessianStructure(int* rows, int* cols) const override;
  void HessianValues(const Eigen::VectorXd& x, double objective_factor, const double* multipliers,
                     double* values) override;

  Eigen::VectorXd WeightedResiduals(const Eigen::VectorXd& x) override;
  // dr/dp along the balance: dz/dp = −(∂R/∂z)⁻¹·∂R/∂p per step.
  Eigen::MatrixXd ReducedResidualJacobian(const Eigen::VectorXd& x) override;
  Eigen::MatrixXd SharedErrorInformation(const Eigen::MatrixXd& reduced_jacobian) const override;
  Eigen::MatrixXd ModelErrorInformation(const Eigen::VectorXd& x, const Eigen::MatrixXd& reduced_jacobian,
                                        int degrees_of_freedom, std::vector<ModelErrorEstimate>* errors) override;

  Eigen::MatrixXcd DisplacementPhasors(const Eigen::VectorXd& x, int step,
                                       const std::vector<double>& positions_m) override;
  Eigen::VectorXcd StepState(const Eigen::VectorXd& x, int step) const override;

 private:
  struct StepCache;
  void Evaluate(const Eigen::VectorXd& x);
  // x with these parameters and states, the scales set from the states.
  Eigen::VectorXd PointFrom(const std::vector<double>& parameters, const std::vector<Eigen::VectorXd>& states);

  FitData data_;
  ModelStructure structure_;
  std::unique_ptr<StepModel> model_;
  int state_size_ = 0;
  ParameterScaling scaling_;  // of the parameters, the first entries of x
  // Per step: the scale of its state and of each of its constraint rows.
  std::vector<double> state_scale_;
  std::vector<Eigen::VectorXd> constraint_scale_;

  Eigen::VectorXd cached_x_;
  std::vector<StepCache> cache_;
  double objective_ = 0.0;
};

}  // namespace beamid::solver
