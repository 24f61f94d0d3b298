#include "solver/estimation/identification_problem.h"

#include "hb/option_checks.h"
#include "solver/estimation/support_reconstruction.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>

#include <Eigen/LU>

namespace beamid::solver {

using hb::Complex;
using hb::HarmonicBalance;
using hb::LinearHarmonics;

struct IdentificationProblem::StepCache {
  Eigen::VectorXd constraint;        // R_i
  Eigen::MatrixXd d_constraint_d_z;  // ∂R_i/∂z_i
  Eigen::MatrixXd d_constraint_d_p;  // ∂R_i/∂p
  Eigen::VectorXd residual;          // r_i
  Eigen::MatrixXd d_residual_d_z;    // ∂r_i/∂z_i
  Eigen::MatrixXd d_residual_d_p;    // ∂r_i/∂p (linear parameters only)
};

namespace {
// Relative nudge of a linear parameter for its difference quotient.
constexpr double kLinearNudge = 1e-6;

}  // namespace

IdentificationProblem::IdentificationProblem(const FitData& data, const ModelStructure& structure,
                                             const ModelOptions& options)
    : data_(data), structure_(structure), options_(options) {
  options_.Validate();
  if (!structure_.law) throw std::invalid_argument("the model structure has no support law");
  if (options_.num_harmonics < data_.num_fit_harmonics)
    throw std::invalid_argument("the model must hold at least the fitted harmonics");
  num_law_ = static_cast<int>(structure_.law_bounds.size());
  num_linear_ = static_cast<int>(structure_.linear.size());
  num_parameters_ = num_law_ + num_linear_;
  state_size_ = 2 * options_.num_harmonics + 1;
  scaling_ = ParameterScaling(structure_.Bounds());
  for (const auto& c : data_.channels) positions_m_.push_back(c.position_m);
  base_model_ = {.beam = data_.beam, .attachments = data_.sensor_masses};
  base_model_.beam.loss_factor = options_.beam_loss_factor;
  balance_ = std::make_unique<HarmonicBalance>(
      hb::LinearBeam(base_model_, data_.force_position_m), *structure_.law,
      hb::HarmonicBalanceOptions{.num_harmonics = options_.num_harmonics,
                                 .num_time_samples = options_.num_time_samples});
  cache_.resize(num_steps());
  theta_scale_rad_.assign(num_steps(), 1e-3);  // refined by FeasiblePoint
  constraint_scale_Nm_.assign(num_steps(), Eigen::VectorXd::Ones(state_size_));
}

IdentificationProblem::~IdentificationProblem() = default;

std::vector<double> IdentificationProblem::Parameters(const Eigen::VectorXd& x) const {
  return scaling_.Physical(x);
}

Eigen::VectorXd IdentificationProblem::States(const Eigen::VectorXd& x, int step) const {
  return x.segment(num_parameters_ + step * state_size_, state_size_) * theta_scale_rad_[step];
}

void IdentificationProblem::UpdateLinear(const std::vector<double>& linear_values) {
  if (linear_valid_ && linear_values == linear_values_) return;
  linear_values_ = linear_values;
  const double max_hz = [&] {
    double m = 0.0;
    for (const auto& s : data_.steps) m = std::max(m, s.omega_rad_s);
    return 1.5 * (options_.num_harmonics + 1) * m / (2.0 * 3.141592653589793);
  }();
  auto build = [&](const std::vector<double>& values) {
    hb::LinearBeamModel model = base_model_;
    for (int j = 0; j < num_linear_; ++j) structure_.linear[j].apply(model, values[j]);
    const hb::LinearBeam beam(model, data_.force_position_m, {.max_frequency_hz = std::max(max_hz, 100.0)});
    std::vector<LinearHarmonics> per_step;
    for (const auto& s : data_.steps)
      per_step.push_back(hb::ComputeLinearHarmonics(beam, s.omega_rad_s, options_.num_harmonics, positions_m_));
    return per_step;
  };
  linear_ = build(linear_values);
  linear_nudged_.assign(num_linear_, {});
  linear_step_.assign(num_linear_, 0.0);
  for (int j = 0; j < num_linear_; ++j) {
    std::vector<double> nudged = linear_values;
    linear_step_[j] = kLinearNudge * std::max(std::abs(linear_values[j]), structure_.linear[j].bounds.typical);
    nudged[j] += linear_step_[j];
    linear_nudged_[j] = build(nudged);
  }
  linear_valid_ = true;
}

Eigen::VectorXd IdentificationProblem::ModelResidual(int step, const Eigen::VectorXd& z,
                                                     const LinearHarmonics& linear) const {
  const FitStep& s = data_.steps[step];
  const Eigen::VectorXcd theta = HarmonicBalance::ToComplex(z);
  const Eigen::VectorXcd force = hb::PadHarmonics(s.force_N, options_.num_harmonics);
  const int channels = static_cast<int>(data_.channels.size());
  const int k_max = data_.num_fit_harmonics;
  Eigen::VectorXd r(2 * channels * k_max);
  for (int c = 0; c < channels; ++c)
    for (int k = 1; k <= k_max; ++k) {
      const Complex model = DerivativeFactor(data_.channels[c].derivative_order, k * s.omega_rad_s) *
                            (linear.displacement_per_force(c, k) * force[k] +
                             linear.displacement_per_rotation(c, k) * theta[k]);
      const Complex misfit = model - s.measured(c, k - 1);
      r.segment<2>(2 * (c * k_max + k - 1)) = s.whitening[c][k - 1] * Eigen::Vector2d(misfit.real(), misfit.imag());
    }
  return r;
}

void IdentificationProblem::Evaluate(const Eigen::VectorXd& x) {
  if (cached_x_.size() == x.size() && cached_x_ == x) return;
  const std::vector<double> p = Parameters(x);
  balance_->SetLawParameters(std::span<const double>(p.data(), num_law_));
  UpdateLinear(std::vector<double>(p.begin() + num_law_, p.end()));
  const int channels = static_cast<int>(data_.channels.size());
  const int k_max = data_.num_fit_harmonics;
  const int h = options_.num_harmonics;
  objective_ = 0.0;
  for (int i = 0; i < num_steps(); ++i) {
    const FitStep& s = data_.steps[i];
    StepCache& c = cache_[i];
    const Eigen::VectorXd z = States(x, i);
    const Eigen::VectorXcd theta = HarmonicBalance::ToComplex(z);
    const Eigen::VectorXcd force = hb::PadHarmonics(s.force_N, h);
    balance_->Residual(z, linear_[i], s.force_N, &c.constraint, &c.d_constraint_d_z);
    c.d_constraint_d_p.resize(state_size_, num_parameters_);
    if (num_law_ > 0) c.d_constraint_d_p.leftCols(num_law_) = balance_->ParameterJacobian(z, s.omega_rad_s);
    c.residual = ModelResidual(i, z, linear_[i]);
    objective_ += 0.5 * c.residual.squaredNorm();
    c.d_residual_d_p = Eigen::MatrixXd::Zero(c.residual.size(), num_parameters_);
    for (int j = 0; j < num_linear_; ++j) {
      const LinearHarmonics& nudged = linear_nudged_[j][i];
      Eigen::VectorXcd d_constraint(h + 1);
      for (int k = 0; k <= h; ++k)
        d_constraint[k] = ((nudged.rotational_stiffness[k] - linear_[i].rotational_stiffness[k]) * theta[k] -
                           (nudged.blocked_moment_per_force[k] - linear_[i].blocked_moment_per_force[k]) * force[k]) /
                          linear_step_[j];
      d_constraint[0] = d_constraint[0].real();
      c.d_constraint_d_p.col(num_law_ + j) = HarmonicBalance::ToReal(d_constraint);
      c.d_residual_d_p.col(num_law_ + j) = (ModelResidual(i, z, nudged) - c.residual) / linear_step_[j];
    }
    // ∂r/∂z: only Re/Im Θ_k of the fitted harmonics enter, through b·(ikω)^d.
    c.d_residual_d_z = Eigen::MatrixXd::Zero(c.residual.size(), state_size_);
    for (int ch = 0; ch < channels; ++ch)
      for (int k = 1; k <= k_max; ++k) {
        const Complex g = DerivativeFactor(data_.channels[ch].derivative_order, k * s.omega_rad_s) *
                          linear_[i].displacement_per_rotation(ch, k);
        const Eigen::Matrix2d& w = s.whitening[ch][k - 1];
        const int row = 2 * (ch * k_max + k - 1);
        c.d_residual_d_z.block<2, 1>(row, 2 * k - 1) = w * Eigen::Vector2d(g.real(), g.imag());
        c.d_residual_d_z.block<2, 1>(row, 2 * k) = w * Eigen::Vector2d(-g.imag(), g.real());
      }
  }
  cached_x_ = x;
}

std::vector<ReconstructedStep> IdentificationProblem::MeasuredRotations(const std::vector<double>& parameters) const {
  try {
    ModelStructure current = structure_;
    current.SetValues(parameters);
    return ReconstructSupport(data_, current.ApplyLinear(base_model_));
  } catch (const std::exception&) {
    return {};  // too few channels to reconstruct: the sweep alone decides
  }
}

Eigen::VectorXd IdentificationProblem::MeasuredStatePoint(const std::vector<double>& parameters) {
  // The feasible point sets the scales and the harmonics the sensors do not
  // resolve (0 and above K); the measured ones replace the rest.
  const std::vector<ReconstructedStep> measured = MeasuredRotations(parameters);
  Eigen::VectorXd x = FeasiblePointFrom(parameters, measured, nullptr);
  if (measured.empty()) return x;
  for (int i = 0; i < num_steps(); ++i) {
    Eigen::VectorXcd theta = HarmonicBalance::ToComplex(States(x, i));
    const Eigen::VectorXcd& m = measured[i].theta_rad;
    for (Eigen::Index k = 1; k < std::min<Eigen::Index>(m.size(), theta.size()); ++k) theta[k] = m[k];
    x.segment(num_parameters_ + i * state_size_, state_size_) = HarmonicBalance::ToReal(theta) / theta_scale_rad_[i];
  }
  cached_x_.resize(0);
  return x;
}

Eigen::VectorXd IdentificationProblem::FeasiblePoint(const std::vector<double>& parameters, int* failed_steps) {
  return FeasiblePointFrom(parameters, MeasuredRotations(parameters), failed_steps);
}

Eigen::VectorXd IdentificationProblem::FeasiblePointFrom(const std::vector<double>& parameters,
                                                         const std::vector<ReconstructedStep>& measured,
                                                         int* failed_steps) {
  if (static_cast<int>(parameters.size()) != num_parameters_)
    throw std::invalid_argument("FeasiblePoint: wrong number of parameters");
  balance_->SetLawParameters(std::span<const double>(parameters.data(), num_law_));
  UpdateLinear(std::vector<double>(parameters.begin() + num_law_, parameters.end()));
  const int h = options_.num_harmonics;
  const double k_law = balance_->law().InitialStiffness_Nm_rad();
  const double c_law = balance_->law().InitialDamping_Nms_rad();
  // Newton started at the support rotation the measurements show lands on
  // the branch the test was on, whatever branch a sweep with far-off
  // parameters would have followed.
  std::vector<Eigen::VectorXd> states(num_steps());
  int failures = 0;
  Eigen::VectorXd previous;
  std::string previous_level;
  for (int i = 0; i < num_steps(); ++i) {
    const FitStep& s = data_.steps[i];
    const LinearHarmonics& linear = linear_[i];
    // Linear guess with the law's small-amplitude stiffness.
    Eigen::VectorXcd theta(h + 1);
    const Eigen::VectorXcd force = hb::PadHarmonics(s.force_N, h);
    for (int k = 0; k <= h; ++k)
      theta[k] = linear.blocked_moment_per_force[k] * force[k] /
                 (linear.rotational_stiffness[k] + Complex(k_law, k * s.omega_rad_s * c_law));
    const Eigen::VectorXd linear_guess = HarmonicBalance::ToReal(theta);
    auto newton = [&](Eigen::VectorXd z) -> std::optional<Eigen::VectorXd> {
      Eigen::VectorXd r;
      Eigen::MatrixXd j;
      for (int iteration = 0; iteration < 60; ++iteration) {
        balance_->Residual(z, linear, s.force_N, &r, &j);
        const Eigen::VectorXd step = j.partialPivLu().solve(-r);
        if (!step.allFinite()) return std::nullopt;
        // Damped: never move |θ| by more than its own size at once.
        const double limit = std::max(z.norm(), 1e-9);
        z += step.norm() > limit ? Eigen::VectorXd(step * (limit / step.norm())) : step;
        if (step.norm() <= 1e-11 * (z.norm() + 1e-15)) return z;
      }
      return std::nullopt;
    };
    std::optional<Eigen::VectorXd> solution;
    if (!measured.empty()) {
      Eigen::VectorXcd theta_measured = Eigen::VectorXcd::Zero(h + 1);
      const Eigen::VectorXcd& m = measured[i].theta_rad;
      for (Eigen::Index k = 1; k < std::min<Eigen::Index>(m.size(), h + 1); ++k) theta_measured[k] = m[k];
      solution = newton(HarmonicBalance::ToReal(theta_measured));
    }
    if (!solution && previous.size() && s.level == previous_level) solution = newton(previous);
    if (!solution) solution = newton(linear_guess);
    if (!solution) {
      ++failures;
      solution = linear_guess;
    }
    states[i] = *solution;
    previous = *solution;
    previous_level = s.level;
  }
  double largest = 0.0;
  for (const auto& z : states) largest = std::max(largest, z.norm());
  for (int i = 0; i < num_steps(); ++i) {
    theta_scale_rad_[i] = std::max(states[i].norm(), 1e-6 * largest + 1e-15);
    // Each harmonic's row by the moment its own stiffness D(kω) takes: D is
    // huge near the clamped–clamped frequencies of a high harmonic, and an
    // unscaled row there would dominate the constraint violation.
    for (int k = 0; k <= h; ++k) {
      const double row = theta_scale_rad_[i] * std::max(std::abs(linear_[i].rotational_stiffness[k]), k_law + 1.0);
      constraint_scale_Nm_[i][k == 0 ? 0 : 2 * k - 1] = row;
      if (k > 0) constraint_scale_Nm_[i][2 * k] = row;
    }
  }
  Eigen::VectorXd x(num_variables());
  scaling_.SetScaled(parameters, &x);
  for (int i = 0; i < num_steps(); ++i)
    x.segment(num_parameters_ + i * state_size_, state_size_) = states[i] / theta_scale_rad_[i];
  cached_x_.resize(0);
  if (failed_steps) *failed_steps = failures;
  return x;
}

void IdentificationProblem::Bounds(Eigen::VectorXd* lower, Eigen::VectorXd* upper) const {
  scaling_.Bounds(num_variables(), lower, upper);
}

double IdentificationProblem::Objective(const Eigen::VectorXd& x) {
  Evaluate(x);
  return objective_;
}

void IdentificationProblem::Gradient(const Eigen::VectorXd& x, Eigen::VectorXd* gradient) {
  Evaluate(x);
  gradient->setZero(num_variables());
  for (int i = 0; i < num_steps(); ++i) {
    const StepCache& c = cache_[i];
    gradient->head(num_parameters_) += c.d_residual_d_p.transpose() * c.residual;
    gradient->segment(num_parameters_ + i * state_size_, state_size_) =
        c.d_residual_d_z.transpose() * c.residual * theta_scale_rad_[i];
  }
  for (int j = 0; j < num_parameters_; ++j) (*gradient)[j] *= scaling_.scale(j);
}

void IdentificationProblem::Constraints(const Eigen::VectorXd& x, Eigen::VectorXd* constraints) {
  Evaluate(x);
  constraints->resize(num_constraints());
  for (int i = 0; i < num_steps(); ++i)
    constraints->segment(i * state_size_, state_size_) = cache_[i].constraint.cwiseQuotient(constraint_scale_Nm_[i]);
}

void IdentificationProblem::JacobianStructure(int* rows, int* cols) const {
  int n = 0;
  for (int i = 0; i < num_steps(); ++i)
    for (int r = 0; r < state_size_; ++r) {
      for (int j = 0; j < num_parameters_; ++j, ++n) {
        rows[n] = i * state_size_ + r;
        cols[n] = j;
      }
      for (int j = 0; j < state_size_; ++j, ++n) {
        rows[n] = i * state_size_ + r;
        cols[n] = num_parameters_ + i * state_size_ + j;
      }
    }
}

void IdentificationProblem::JacobianValues(const Eigen::VectorXd& x, double* values) {
  Evaluate(x);
  int n = 0;
  for (int i = 0; i < num_steps(); ++i) {
    const StepCache& c = cache_[i];
    for (int r = 0; r < state_size_; ++r) {
      const double row_scale = 1.0 / constraint_scale_Nm_[i][r];
      for (int j = 0; j < num_parameters_; ++j)
        values[n++] = c.d_constraint_d_p(r, j) * scaling_.scale(j) * row_scale;
      for (int j = 0; j < state_size_; ++j) values[n++] = c.d_constraint_d_z(r, j) * theta_scale_rad_[i] * row_scale;
    }
  }
}

int IdentificationProblem::HessianNonZeros() const {
  const int p = num_parameters_, m = state_size_;
  return p * (p + 1) / 2 + num_steps() * (m * p + m * (m + 1) / 2);
}

void IdentificationProblem::HessianStructure(int* rows, int* cols) const {
  int n = 0;
  for (int r = 0; r < num_parameters_; ++r)
    for (int c = 0; c <= r; ++c, ++n) {
      rows[n] = r;
      cols[n] = c;
    }
  for (int i = 0; i < num_steps(); ++i) {
    const int offset = num_parameters_ + i * state_size_;
    for (int r = 0; r < state_size_; ++r) {
      for (int c = 0; c < num_parameters_; ++c, ++n) {
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

void IdentificationProblem::HessianValues(const Eigen::VectorXd& x, double objective_factor,
                                          const double* multipliers, double* values) {
  Evaluate(x);
  const int p = num_parameters_, m = state_size_, h = options_.num_harmonics;
  const std::vector<double> parameters = Parameters(x);
  Eigen::MatrixXd hpp = Eigen::MatrixXd::Zero(p, p);
  int n = p * (p + 1) / 2;
  for (int i = 0; i < num_steps(); ++i) {
    const StepCache& c = cache_[i];
    const FitStep& s = data_.steps[i];
    // Objective, Gauss–Newton, physical units.
    Eigen::MatrixXd hzz = objective_factor * c.d_residual_d_z.transpose() * c.d_residual_d_z;
    Eigen::MatrixXd hzp = objective_factor * c.d_residual_d_z.transpose() * c.d_residual_d_p;
    hpp += objective_factor * c.d_residual_d_p.transpose() * c.d_residual_d_p;
    // Constraints: the gradient of μᵀR (μ = λ / ρ) w.r.t. (p_law, z), differenced.
    const Eigen::VectorXd mu =
        Eigen::Map<const Eigen::VectorXd>(multipliers + i * m, m).cwiseQuotient(constraint_scale_Nm_[i]);
    const Eigen::VectorXd z = States(x, i);
    auto gradient = [&](const Eigen::VectorXd& zz, const std::vector<double>& law) {
      balance_->SetLawParameters(law);
      Eigen::VectorXd r;
      Eigen::MatrixXd jz;
      balance_->Residual(zz, linear_[i], s.force_N, &r, &jz);
      Eigen::VectorXd g(num_law_ + m);
      g.head(num_law_) = balance_->ParameterJacobian(zz, s.omega_rad_s).transpose() * mu;
      g.tail(m) = jz.transpose() * mu;
      return g;
    };
    const std::vector<double> law(parameters.begin(), parameters.begin() + num_law_);
    Eigen::MatrixXd second = Eigen::MatrixXd::Zero(num_law_ + m, num_law_ + m);
    for (int j = 0; j < (options_.constraint_curvature ? num_law_ + m : 0); ++j) {
      const bool is_law = j < num_law_;
      const double step = 1e-6 * (is_law ? scaling_.scale(j) : theta_scale_rad_[i]);
      Eigen::VectorXd z_up = z, z_down = z;
      std::vector<double> law_up = law, law_down = law;
      if (is_law) {
        law_up[j] += step;
        law_down[j] -= step;
      } else {
        z_up[j - num_law_] += step;
        z_down[j - num_law_] -= step;
      }
      second.col(j) = (gradient(z_up, law_up) - gradient(z_down, law_down)) / (2.0 * step);
    }
    balance_->SetLawParameters(law);
    second = 0.5 * (second + second.transpose()).eval();
    hpp.topLeftCorner(num_law_, num_law_) += second.topLeftCorner(num_law_, num_law_);
    hzp.leftCols(num_law_) += second.bottomLeftCorner(m, num_law_);
    hzz += second.bottomRightCorner(m, m);
    // Linear parameters enter R as D(p_l)·Θ − B(p_l)·F: a cross term with z only.
    for (int j = 0; j < (options_.constraint_curvature ? num_linear_ : 0); ++j) {
      const hb::LinearHarmonics& nudged = linear_nudged_[j][i];
      Eigen::VectorXd column = Eigen::VectorXd::Zero(m);
      for (int k = 0; k <= h; ++k) {
        const Complex d = (nudged.rotational_stiffness[k] - linear_[i].rotational_stiffness[k]) / linear_step_[j];
        if (k == 0) {
          column[0] = d.real() * mu[0];
          continue;
        }
        // ∂/∂(Re Θ, Im Θ) of μ_re·Re(dΘ) + μ_im·Im(dΘ).
        column[2 * k - 1] = d.real() * mu[2 * k - 1] + d.imag() * mu[2 * k];
        column[2 * k] = -d.imag() * mu[2 * k - 1] + d.real() * mu[2 * k];
      }
      hzp.col(num_law_ + j) += column;
    }
    // Into scaled variables and the lower-triangle layout.
    const double sz = theta_scale_rad_[i];
    for (int r = 0; r < m; ++r) {
      for (int q = 0; q < p; ++q) values[n++] = hzp(r, q) * sz * scaling_.scale(q);
      for (int q = 0; q <= r; ++q) values[n++] = hzz(r, q) * sz * sz;
    }
  }
  n = 0;
  for (int r = 0; r < p; ++r)
    for (int q = 0; q <= r; ++q) values[n++] = hpp(r, q) * scaling_.scale(r) * scaling_.scale(q);
}

Eigen::VectorXd IdentificationProblem::WeightedResiduals(const Eigen::VectorXd& x) {
  Evaluate(x);
  Eigen::VectorXd r(num_residuals());
  int offset = 0;
  for (const StepCache& c : cache_) {
    r.segment(offset, c.residual.size()) = c.residual;
    offset += static_cast<int>(c.residual.size());
  }
  return r;
}

Eigen::MatrixXd IdentificationProblem::ReducedResidualJacobian(const Eigen::VectorXd& x) {
  Evaluate(x);
  Eigen::MatrixXd j(num_residuals(), num_parameters_);
  int offset = 0;
  for (const StepCache& c : cache_) {
    // dz/dp = −(∂R/∂z)⁻¹ ∂R/∂p on the constraint manifold.
    const Eigen::MatrixXd dz_dp = -c.d_constraint_d_z.partialPivLu().solve(c.d_constraint_d_p);
    j.middleRows(offset, c.residual.size()) = c.d_residual_d_p + c.d_residual_d_z * dz_dp;
    offset += static_cast<int>(c.residual.size());
  }
  return j;
}

Eigen::MatrixXcd IdentificationProblem::DisplacementPhasors(const Eigen::VectorXd& x, int step,
                                                            const std::vector<double>& positions_m) {
  const std::vector<double> p = Parameters(x);
  hb::LinearBeamModel model = base_model_;
  for (int j = 0; j < num_linear_; ++j) structure_.linear[j].apply(model, p[num_law_ + j]);
  const hb::LinearBeam beam(model, data_.force_position_m);
  const FitStep& s = data_.steps[step];
  const LinearHarmonics linear = hb::ComputeLinearHarmonics(beam, s.omega_rad_s, options_.num_harmonics, positions_m);
  const Eigen::VectorXcd theta = HarmonicBalance::ToComplex(States(x, step));
  const Eigen::VectorXcd force = hb::PadHarmonics(s.force_N, options_.num_harmonics);
  return linear.displacement_per_force * force.asDiagonal() + linear.displacement_per_rotation * theta.asDiagonal();
}

}  // namespace beamid::solver
