#include "hb/time_simulator.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include <Eigen/Eigenvalues>

namespace beamid::hb {

TimeSimulator::TimeSimulator(const TimeSimulatorModel& model, const SupportLaw& law,
                             const TimeSimulatorOptions& options)
    : fe_beam_(model.beam, model.attachments,
               [&] {
                 std::vector<double> nodes = model.output_positions_m;
                 nodes.push_back(model.force_position_m);
                 return nodes;
               }(),
               options.mesh),
      law_(law.Clone()),
      time_step_s_(options.time_step_s),
      max_newton_iterations_(options.max_newton_iterations) {
  if (!(time_step_s_ > 0.0 && std::isfinite(time_step_s_)))
    throw std::invalid_argument("time simulator: time_step_s must be a positive number");
  const int force_dof = fe_beam_.DeflectionDof(model.force_position_m);
  if (force_dof == FeBeam::kConstrained)
    throw std::invalid_argument("time simulator: the force acts at a constrained point (x = 0 or a rigid support)");

  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> modes(fe_beam_.Stiffness(), fe_beam_.Mass());
  if (modes.info() != Eigen::Success) throw std::runtime_error("time simulator: modal decomposition failed");
  const Eigen::MatrixXd& phi = modes.eigenvectors();  // Φᵀ M Φ = I
  modal_stiffness_ = modes.eigenvalues().array().max(0.0);
  omega_ = modal_stiffness_.sqrt();

  if (options.damping_reference_rad_s > 0.0) {
    damping_reference_rad_s_ = options.damping_reference_rad_s;
  } else {
    damping_reference_rad_s_ = fe_beam_.NaturalFrequencies_rad_s(1, law_->InitialStiffness_Nm_rad()).at(0);
  }
  beta_damping_s_ = model.beam.loss_factor / damping_reference_rad_s_;
  modal_damping_ = beta_damping_s_ * modal_stiffness_;

  const double dt = time_step_s_;
  inv_effective_mass_ = (1.0 + modal_damping_ * (0.5 * dt) + modal_stiffness_ * (0.25 * dt * dt)).inverse();
  force_shape_ = phi.row(force_dof).transpose().array();
  rotation_shape_ = phi.row(fe_beam_.SupportRotationDof()).transpose().array();
  output_modes_ = Eigen::MatrixXd::Zero(static_cast<int>(model.output_positions_m.size()), phi.cols());
  for (size_t i = 0; i < model.output_positions_m.size(); ++i) {
    const int dof = fe_beam_.DeflectionDof(model.output_positions_m[i]);
    if (dof != FeBeam::kConstrained) output_modes_.row(static_cast<int>(i)) = phi.row(dof);
  }
  moment_flexibility_ = 0.25 * dt * dt * (rotation_shape_.square() * inv_effective_mass_).sum();
  Reset(0.0);
}

void TimeSimulator::Reset(double force_N) {
  const int n = static_cast<int>(omega_.size());
  state_ = State{};
  state_.modal_displacement = Eigen::ArrayXd::Zero(n);
  state_.modal_velocity = Eigen::ArrayXd::Zero(n);
  state_.modal_acceleration = force_shape_ * force_N;  // the law's moment is 0 at rest
  state_.law_state.assign(law_->NumInternalStates(), 0.0);
  state_.force_N = force_N;
}

double TimeSimulator::SolveSupport(double theta_predicted, double* moment_Nm,
                                   std::vector<double>& law_state_out) const {
  const double g = moment_flexibility_;
  const double rate_per_theta = 2.0 / time_step_s_;
  const double theta_n = state_.theta_rad;
  const double rate_n = state_.theta_rate_rad_s;
  // r(θ) = θ − θ_pred + g·M_s(θ, θ̇(θ)); r is increasing for any law whose
  // tangents are non-negative, which Newton exploits and bisection relies on.
  auto residual = [&](double theta, double* slope, double* moment) {
    const SupportLawResponse r =
        law_->Evaluate(theta, rate_per_theta * (theta - theta_n) - rate_n, state_.law_state, law_state_out);
    *moment = r.moment_Nm;
    *slope = 1.0 + g * (r.d_moment_d_theta_Nm_rad + rate_per_theta * r.d_moment_d_theta_rate_Nms_rad);
    return theta - theta_predicted + g * r.moment_Nm;
  };
  double theta = theta_predicted - g * state_.support_moment_Nm;
  double slope = 1.0;
  for (int it = 0; it < max_newton_iterations_; ++it) {
    const double r = residual(theta, &slope, moment_Nm);
    const double tolerance = 1e-14 * (std::abs(theta_predicted) + std::abs(theta) + g * std::abs(*moment_Nm)) + 1e-300;
    if (std::abs(r) <= tolerance) return theta;
    if (!(slope > 0.0) || !std::isfinite(r)) break;
    const double step = r / slope;
    theta -= step;
    if (std::abs(step) <= tolerance) {
      residual(theta, &slope, moment_Nm);
      return theta;
    }
  }
  // Newton did not settle (a kink visited back and forth): bracket and bisect.
  double scale = std::max({std::abs(theta_predicted), std::abs(theta_n), 1e-12});
  double lo = theta_predicted - scale, hi = theta_predicted + scale;
  double moment = 0.0;
  for (int i = 0; i < 200 && residual(lo, &slope, &moment) > 0.0; ++i) lo -= (scale *= 2.0);
  for (int i = 0; i < 200 && residual(hi, &slope, &moment) < 0.0; ++i) hi += (scale *= 2.0);
  if (!(residual(lo, &slope, &moment) <= 0.0 && residual(hi, &slope, &moment) >= 0.0))
    throw std::runtime_error("time simulator: the support equation has no solution at t = " +
                             std::to_string(state_.time_s) + " s (law " + law_->Name() + ")");
  for (int i = 0; i < 200 && hi - lo > 1e-15 * (std::abs(lo) + std::abs(hi)); ++i) {
    const double mid = 0.5 * (lo + hi);
    (residual(mid, &slope, &moment) > 0.0 ? hi : lo) = mid;
  }
  theta = 0.5 * (lo + hi);
  residual(theta, &slope, moment_Nm);
  return theta;
}

void TimeSimulator::Advance(double force_N) {
  const double dt = time_step_s_;
  State& s = state_;
  // Newmark predictors; a_{n+1} = a0 − (φ_θ/m̂)·M_s is linear in the moment.
  const Eigen::ArrayXd u_pred = s.modal_displacement + dt * s.modal_velocity + (0.25 * dt * dt) * s.modal_acceleration;
  const Eigen::ArrayXd v_pred = s.modal_velocity + (0.5 * dt) * s.modal_acceleration;
  const Eigen::ArrayXd a_free =
      (force_shape_ * force_N - modal_damping_ * v_pred - modal_stiffness_ * u_pred) * inv_effective_mass_;
  const double theta_predicted = (rotation_shape_ * (u_pred + (0.25 * dt * dt) * a_free)).sum();

  std::vector<double> law_state_out(s.law_state.size());
  double moment_Nm = 0.0;
  const double theta = SolveSupport(theta_predicted, &moment_Nm, law_state_out);

  s.modal_acceleration = a_free - (rotation_shape_ * inv_effective_mass_) * moment_Nm;
  s.modal_displacement = u_pred + (0.25 * dt * dt) * s.modal_acceleration;
  s.modal_velocity = v_pred + (0.5 * dt) * s.modal_acceleration;
  s.theta_rate_rad_s = (2.0 / dt) * (theta - s.theta_rad) - s.theta_rate_rad_s;
  s.theta_rad = theta;
  s.support_moment_Nm = moment_Nm;
  s.law_state = std::move(law_state_out);
  s.force_N = force_N;
  s.time_s += dt;
}

void TimeSimulator::Outputs(Eigen::Ref<Eigen::VectorXd> displacement_m, Eigen::Ref<Eigen::VectorXd> velocity_m_s,
                            Eigen::Ref<Eigen::VectorXd> acceleration_m_s2) const {
  displacement_m.noalias() = output_modes_ * state_.modal_displacement.matrix();
  velocity_m_s.noalias() = output_modes_ * state_.modal_velocity.matrix();
  acceleration_m_s2.noalias() = output_modes_ * state_.modal_acceleration.matrix();
}

}  // namespace beamid::hb
