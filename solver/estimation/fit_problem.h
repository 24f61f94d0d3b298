// The interface between a model fitted to a campaign and the optimiser: a
// constrained least-squares program in scaled variables
//     min ½·|r(x)|²   s.t.   c(x) = 0,   l ≤ x ≤ u,
// x = [parameters; per-step states], one block of constraints per step
// (the model's equations there). SteppedFitProblem (stepped_fit_problem.h)
// implements it once for every model family from the family's model of one
// step (IdentificationProblem: exact harmonic balance; MultipleScalesProblem:
// the seed's model); solver/internal/ipopt_program.* runs Ipopt on it and
// solver/identify.* does the rest (starts, covariance) through it alone.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "solver/estimation/model_error.h"
#include "solver/estimation/model_structure.h"

namespace beamid::solver {

class FitProblem {
 public:
  virtual ~FitProblem() = default;

  virtual int num_parameters() const = 0;
  virtual int num_variables() const = 0;
  virtual int num_constraints() const = 0;
  virtual int num_residuals() const = 0;
  virtual int num_steps() const = 0;

  // Physical parameters of a scaled point.
  virtual std::vector<double> Parameters(const Eigen::VectorXd& x) const = 0;
  // A point with these parameters whose states satisfy the constraints as
  // well as the model allows (the count of steps where that failed).
  virtual Eigen::VectorXd FeasiblePoint(const std::vector<double>& parameters, int* failed_steps = nullptr) = 0;
  // A point with these parameters whose states are the ones the
  // measurements show (not, in general, feasible): a start on the measured
  // branch whatever the parameters. Models that cannot reconstruct their
  // states from the data return FeasiblePoint's.
  virtual Eigen::VectorXd MeasuredStatePoint(const std::vector<double>& parameters) {
    return FeasiblePoint(parameters);
  }
  virtual void Bounds(Eigen::VectorXd* lower, Eigen::VectorXd* upper) const = 0;

  virtual double Objective(const Eigen::VectorXd& x) = 0;
  virtual void Gradient(const Eigen::VectorXd& x, Eigen::VectorXd* gradient) = 0;
  virtual void Constraints(const Eigen::VectorXd& x, Eigen::VectorXd* constraints) = 0;
  virtual int JacobianNonZeros() const = 0;
  virtual void JacobianStructure(int* rows, int* cols) const = 0;
  virtual void JacobianValues(const Eigen::VectorXd& x, double* values) = 0;
  // Hessian of σ·f + Σ λ_j c_j, lower triangle.
  virtual int HessianNonZeros() const = 0;
  virtual void HessianStructure(int* rows, int* cols) const = 0;
  virtual void HessianValues(const Eigen::VectorXd& x, double objective_factor, const double* multipliers,
                             double* values) = 0;

  // Whitened residuals, and their Jacobian w.r.t. the physical parameters
  // with the states eliminated through the constraints (for the covariance).
  virtual Eigen::VectorXd WeightedResiduals(const Eigen::VectorXd& x) = 0;
  virtual Eigen::MatrixXd ReducedResidualJacobian(const Eigen::VectorXd& x) = 0;
  // Jᵀ·(Σ − I)·J for that Jacobian J, Σ the whitened residuals' covariance:
  // what errors shared across residuals add to the information a
  // phasor-by-phasor whitening counts (shared_step_errors.h). Zero when
  // the residuals are independent.
  virtual Eigen::MatrixXd SharedErrorInformation(const Eigen::MatrixXd& reduced_jacobian) const {
    return Eigen::MatrixXd::Zero(reduced_jacobian.cols(), reduced_jacobian.cols());
  }
  // The residual model error per fitted harmonic at x (model_error.h) into
  // `errors`, and what it adds to JᵀJ for the reduced Jacobian J, for data
  // whose phasors' σ are calibrated (PhasorUncertainty::kPropagated); no
  // estimates and zero otherwise: the relative floor stands in for it.
  virtual Eigen::MatrixXd ModelErrorInformation(const Eigen::VectorXd& /*x*/, const Eigen::MatrixXd& reduced_jacobian,
                                                int /*degrees_of_freedom*/, std::vector<ModelErrorEstimate>* errors) {
    errors->clear();
    return Eigen::MatrixXd::Zero(reduced_jacobian.cols(), reduced_jacobian.cols());
  }

  // What a report and `beamid predict` need of the fitted model.
  virtual const ModelStructure& structure() const = 0;
  // The highest harmonic the model gives (H).
  virtual int num_model_harmonics() const = 0;
  // Displacement phasors of harmonics 0..H at positions for step i [m]
  // (positions × (H + 1)), with the parameters and states of x.
  virtual Eigen::MatrixXcd DisplacementPhasors(const Eigen::VectorXd& x, int step,
                                               const std::vector<double>& positions_m) = 0;
  // Step i's state as complex phasors in physical units: the harmonics
  // Θ_0..Θ_H of θ for harmonic balance, the modal phasor U for multiple
  // scales (its family names it in result.json).
  virtual Eigen::VectorXcd StepState(const Eigen::VectorXd& x, int step) const = 0;
};

}  // namespace beamid::solver
