#include "solver/estimation/stepped_fit_problem.h"

#include "solver/estimation/model_phasors.h"
#include "solver/estimation/shared_step_errors.h"
#include "solver/estimation/whitened_misfit.h"

#include <algorithm>
#include <stdexcept>

#include <Eigen/LU>

namespace beamid::solver {

using Complex = std::complex<double>;

// Per step, physical units: the balance R_i and the whitened misfit r_i,
// and their derivatives in z_i and in the parameters.
struct SteppedFitProblem::StepCache {
  Eigen::VectorXd constraint;        // R_i
  Eigen::MatrixXd d_constraint_d_z;  // ∂R_i/∂z_i
  Eigen::MatrixXd d_constraint_d_p;  // ∂R_i/∂p
  Eigen::VectorXd residual;          // r_i
  Eigen::MatrixXd d_residual_d_z;    // ∂r_i/∂z_i
  Eigen::MatrixXd d_residual_d_p;    // ∂r_i/∂p
};

Eigen::VectorXd WhitenedMisfit(const FitData& data, int step, const Eigen::VectorXcd& sensors) {
  const FitStep& s = data.steps[step];
  const int channels = static_cast<int>(data.channels.size());
  const int k_max = data.num_fit_harmonics;
  Eigen::VectorXd r(2 * channels * k_max);
  for (int c = 0; c < channels; ++c)
    for (int k = 1; k <= k_max; ++k) {
      const int at = c * k_max + k - 1;
      const Complex misfit =
          DerivativeFactor(data.channels[c].derivative_order, k * s.omega_rad_s) * sensors[at] - s.measured(c, k - 1);
      r.segment<2>(2 * at) = Whitened(s, c, k, misfit);
    }
  return r;
}

Eigen::MatrixXd WhitenedDerivative(const FitData& data, int step, const Eigen::MatrixXcd& sensors_derivative) {
  const FitStep& s = data.steps[step];
  const int channels = static_cast<int>(data.channels.size());
  const int k_max = data.num_fit_harmonics;
  Eigen::MatrixXd d(2 * channels * k_max, sensors_derivative.cols());
  for (int c = 0; c < channels; ++c)
    for (int k = 1; k <= k_max; ++k) {
      const int at = c * k_max + k - 1;
      const Complex g = DerivativeFactor(data.channels[c].derivative_order, k * s.omega_rad_s);
      const Eigen::Matrix2d& w = s.whitening[c][k - 1];
      for (Eigen::Index j = 0; j < sensors_derivative.cols(); ++j) {
        const Complex v = g * sensors_derivative(at, j);
        d.block<2, 1>(2 * at, j) = w * Eigen::Vector2d(v.real(), v.imag());
      }
    }
  return d;
}

SteppedFitProblem::SteppedFitProblem(const FitData& data, const ModelStructure& structure,
                                     const StepModelFactory& make_model)
    : data_(data), structure_(structure), model_(make_model(data_, structure_)) {
  state_size_ = model_->state_size();
  scaling_ = ParameterScaling(structure_.Bounds());
  cache_.resize(num_steps());
  state_scale_.assign(num_steps(), model_->TypicalStateSize());  // refined by FeasiblePoint
  constraint_scale_.assign(num_steps(), Eigen::VectorXd::Ones(state_size_));
}

SteppedFitProblem::~SteppedFitProblem() = default;

std::vector<double> SteppedFitProblem::Parameters(const Eigen::VectorXd& x) const { return scaling_.Physical(x); }

Eigen::VectorXd SteppedFitProblem::States(const Eigen::VectorXd& x, int step) const {
  return x.segment(num_parameters() + step * state_size_, state_size_) * state_scale_[step];
}

Eigen::VectorXcd SteppedFitProblem::StepState(const Eigen::VectorXd& x, int step) const {
  return model_->StepState(States(x, step));
}

void SteppedFitProblem::Evaluate(const Eigen::VectorXd& x) {
  if (cached_x_.size() == x.size() && cached_x_ == x) return;
  model_->SetParameters(Parameters(x));
  objective_ = 0.0;
  StepModel::Values v;
  for (int i = 0; i < num_steps(); ++i) {
    model_->Evaluate(i, States(x, i), state_scale_[i], &v);
    StepCache& c = cache_[i];
    c.constraint = v.balance;
    c.d_constraint_d_z = v.balance_d_state;
    c.d_constraint_d_p = v.balance_d_parameters;
    c.residual = WhitenedMisfit(data_, i, v.sensors);
    c.d_residual_d_z = WhitenedDerivative(data_, i, v.sensors_d_state);
    c.d_residual_d_p = WhitenedDerivative(data_, i, v.sensors_d_parameters);
    objective_ += 0.5 * c.residual.squaredNorm();
  }
  cached_x_ = x;
}

Eigen::VectorXd SteppedFitProblem::PointFrom(const std::vector<double>& parameters,
                                             const std::vector<Eigen::VectorXd>& states) {
  double largest = 0.0;
  for (const auto& z : states) largest = std::max(largest, z.norm());
  for (int i = 0; i < num_steps(); ++i) {
    state_scale_[i] = std::max(states[i].norm(), 1e-6 * largest + 1e-15);
    constraint_scale_[i] = model_->BalanceScale(i, states[i], state_scale_[i]);
  }
  Eigen::VectorXd x(num_variables());
  scaling_.SetScaled(parameters, &x);
  for (int i = 0; i < num_steps(); ++i)
    x.segment(num_parameters() + i * state_size_, state_size_) = states[i] / state_scale_[i];
  cached_x_.resize(0);
  return x;
}

Eigen::VectorXd SteppedFitProblem::FeasiblePoint(const std::vector<double>& parameters, int* failed_steps) {
  if (static_cast<int>(parameters.size()) != num_parameters())
    throw std::invalid_argument("FeasiblePoint: wrong number of parameters");
  return PointFrom(parameters, model_->SolveStates(parameters, failed_steps, nullptr));
}

Eigen::VectorXd SteppedFitProblem::MeasuredStatePoint(const std::vector<double>& parameters) {
  if (static_cast<int>(parameters.size()) != num_parameters())
    throw std::invalid_argument("MeasuredStatePoint: wrong number of parameters");
  // The feasible states set the scales; the measured ones replace them.
  std::vector<Eigen::VectorXd> measured;
  Eigen::VectorXd x = PointFrom(parameters, model_->SolveStates(parameters, nullptr, &measured));
  if (measured.empty()) return x;
  for (int i = 0; i < num_steps(); ++i)
    x.segment(num_parameters() + i * state_size_, state_size_) = measured[i] / state_scale_[i];
  return x;
}

void SteppedFitProblem::Bounds(Eigen::VectorXd* lower, Eigen::VectorXd* upper) const {
  scaling_.Bounds(num_variables(), lower, upper);
}

double SteppedFitProblem::Objective(const Eigen::VectorXd& x) {
  Evaluate(x);
  return objective_;
}

void SteppedFitProblem::Gradient(const Eigen::VectorXd& x, Eigen::VectorXd* gradient) {
  Evaluate(x);
  const int p = num_parameters();
  gradient->setZero(num_variables());
  for (int i = 0; i < num_steps(); ++i) {
    const StepCache& c = cache_[i];
    gradient->head(p) += c.d_residual_d_p.transpose() * c.residual;
    gradient->segment(p + i * state_size_, state_size_) = c.d_residual_d_z.transpose() * c.residual * state_scale_[i];
  }
  for (int j = 0; j < p; ++j) (*gradient)[j] *= scaling_.scale(j);
}

void SteppedFitProblem::Constraints(const Eigen::VectorXd& x, Eigen::VectorXd* constraints) {
  Evaluate(x);
  constraints->resize(num_constraints());
  for (int i = 0; i < num_steps(); ++i)
    constraints->segment(i * state_size_, state_size_) = cache_[i].constraint.cwiseQuotient(constraint_scale_[i]);
}

void SteppedFitProblem::JacobianStructure(int* rows, int* cols) const {
  const int p = num_parameters();
  int n = 0;
  for (int i = 0; i < num_steps(); ++i)
    for (int r = 0; r < state_size_; ++r) {
      for (int j = 0; j < p; ++j, ++n) {
        rows[n] = i * state_size_ + r;
        cols[n] = j;
      }
      for (int j = 0; j < state_size_; ++j, ++n) {
        rows[n] = i * state_size_ + r;
        cols[n] = p + i * state_size_ + j;
      }
    }
}

void SteppedFitProblem::JacobianValues(const Eigen::VectorXd& x, double* values) {
  Evaluate(x);
  int n = 0;
  for (int i = 0; i < num_steps(); ++i) {
    const StepCache& c = cache_[i];
    for (int r = 0; r < state_size_; ++r) {
      const double row_scale = 1.0 / constraint_scale_[i][r];
      for (int j = 0; j < num_parameters(); ++j) values[n++] = c.d_constraint_d_p(r, j) * scaling_.scale(j) * row_scale;
      for (int j = 0; j < state_size_; ++j) values[n++] = c.d_constraint_d_z(r, j) * state_scale_[i] * row_scale;
    }
  }
}

int SteppedFitProblem::HessianNonZeros() const {
  const int p = num_parameters(), m = state_size_;
  return p * (p + 1) / 2 + num_steps() * (m * p + m * (m + 1) / 2);
}

void SteppedFitProblem::HessianStructure(int* rows, int* cols) const {
  const int p = num_parameters();
  int n = 0;
  for (int r = 0; r < p; ++r)
    for (int c = 0; c <= r; ++c, ++n) {
      rows[n] = r;
      cols[n] = c;
    }
  for (int i = 0; i < num_steps(); ++i) {
    const int offset = p + i * state_size_;
    for (int r = 0; r < state_size_; ++r) {
      for (int c = 0; c < p; ++c, ++n) {
        rows[n] = offset + r;
        cols[n] = c;
      }
      for (int c = 0; c <= r; ++c, ++n) {
        rows[n] = offset + r;
        cols[n] = offset + c;
      }
    }
  }
}

void SteppedFitProblem::HessianValues(const Eigen::VectorXd& x, double objective_factor, const double* multipliers,
                                      double* values) {
  Evaluate(x);
  const int p = num_parameters(), m = state_size_;
  Eigen::MatrixXd hpp = Eigen::MatrixXd::Zero(p, p);
  Eigen::MatrixXd second;
  int n = p * (p + 1) / 2;
  for (int i = 0; i < num_steps(); ++i) {
    const StepCache& c = cache_[i];
    // Objective, Gauss–Newton, physical units.
    Eigen::MatrixXd hzz = objective_factor * c.d_residual_d_z.transpose() * c.d_residual_d_z;
    Eigen::MatrixXd hzp = objective_factor * c.d_residual_d_z.transpose() * c.d_residual_d_p;
    hpp += objective_factor * c.d_residual_d_p.transpose() * c.d_residual_d_p;
    // The balance's curvature, weighted by μ = λ / ρ (the rows' scales).
    const Eigen::VectorXd mu =
        Eigen::Map<const Eigen::VectorXd>(multipliers + i * m, m).cwiseQuotient(constraint_scale_[i]);
    if (model_->BalanceCurvature(i, States(x, i), state_scale_[i], mu, &second)) {
      hpp += second.topLeftCorner(p, p);
      hzp += second.bottomLeftCorner(m, p);
      hzz += second.bottomRightCorner(m, m);
    }
    // Into scaled variables and the lower-triangle layout.
    const double sz = state_scale_[i];
    for (int r = 0; r < m; ++r) {
      for (int q = 0; q < p; ++q) values[n++] = hzp(r, q) * sz * scaling_.scale(q);
      for (int q = 0; q <= r; ++q) values[n++] = hzz(r, q) * sz * sz;
    }
  }
  n = 0;
  for (int r = 0; r < p; ++r)
    for (int q = 0; q <= r; ++q) values[n++] = hpp(r, q) * scaling_.scale(r) * scaling_.scale(q);
}

Eigen::VectorXd SteppedFitProblem::WeightedResiduals(const Eigen::VectorXd& x) {
  Evaluate(x);
  Eigen::VectorXd r(num_residuals());
  int offset = 0;
  for (const StepCache& c : cache_) {
    r.segment(offset, c.residual.size()) = c.residual;
    offset += static_cast<int>(c.residual.size());
  }
  return r;
}

Eigen::MatrixXd SteppedFitProblem::ReducedResidualJacobian(const Eigen::VectorXd& x) {
  Evaluate(x);
  Eigen::MatrixXd j(num_residuals(), num_parameters());
  int offset = 0;
  for (const StepCache& c : cache_) {
    // dz/dp = −(∂R/∂z)⁻¹ ∂R/∂p on the constraint manifold.
    const Eigen::MatrixXd dz_dp = -c.d_constraint_d_z.partialPivLu().solve(c.d_constraint_d_p);
    j.middleRows(offset, c.residual.size()) = c.d_residual_d_p + c.d_residual_d_z * dz_dp;
    offset += static_cast<int>(c.residual.size());
  }
  return j;
}

Eigen::MatrixXd SteppedFitProblem::SharedErrorInformation(const Eigen::MatrixXd& reduced_jacobian) const {
  return solver::SharedErrorInformation(data_, reduced_jacobian);
}

Eigen::MatrixXd SteppedFitProblem::ModelErrorInformation(const Eigen::VectorXd& x,
                                                         const Eigen::MatrixXd& reduced_jacobian,
                                                         int degrees_of_freedom,
                                                         std::vector<ModelErrorEstimate>* errors) {
  if (data_.uncertainty != PhasorUncertainty::kPropagated)
    return FitProblem::ModelErrorInformation(x, reduced_jacobian, degrees_of_freedom, errors);
  const std::vector<Eigen::MatrixXcd> model = ModelPhasors(data_, *this, x);
  *errors = EstimateModelErrors(data_, model, degrees_of_freedom);
  return solver::ModelErrorInformation(data_, model, *errors, reduced_jacobian);
}

Eigen::MatrixXcd SteppedFitProblem::DisplacementPhasors(const Eigen::VectorXd& x, int step,
                                                        const std::vector<double>& positions_m) {
  return model_->DisplacementPhasors(Parameters(x), step, States(x, step), positions_m);
}

}  // namespace beamid::solver
