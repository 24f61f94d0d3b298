#include "hb/time_simulator.h"

#include "hb/errors.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

#include <Eigen/Eigenvalues>
#include <unsupported/Eigen/MatrixFunctions>

#include "hb/option_checks.h"

namespace beamid::hb {
namespace {

// The one-step map of one mode q̈ + c·q̇ + ω²·q = p(t):
//     q_{n+1} = uu·q_n + uv·q̇_n + u0·p_n + u1·p_{n+1},  likewise q̇_{n+1}.
struct ModalStepMap {
  double uu, uv, u0, u1, vu, vv, v0, v1;
};

// Modes with ωΔt above this are stepped by Newmark's average acceleration:
// they respond quasi-statically to the test's harmonics, where its period
// error does not matter, while an exact step of a mode near 2π/Δt would
// resonate with the images of the held load and alias onto the harmonics.
constexpr double kExactStepLimit = 0.1;

// Newmark's average acceleration (γ = 1/2, β = 1/4) is linear in (q, q̇, p_n,
// p_{n+1}): its map is read off by stepping unit inputs.
ModalStepMap NewmarkModalStep(double omega, double damping, double dt) {
  const double w2 = omega * omega;
  auto step = [&](double u, double v, double p0, double p1, double* u_out, double* v_out) {
    const double a0 = p0 - damping * v - w2 * u;
    const double u_pred = u + dt * v + 0.25 * dt * dt * a0, v_pred = v + 0.5 * dt * a0;
    const double a1 = (p1 - damping * v_pred - w2 * u_pred) / (1.0 + 0.5 * dt * damping + 0.25 * dt * dt * w2);
    *u_out = u_pred + 0.25 * dt * dt * a1;
    *v_out = v_pred + 0.5 * dt * a1;
  };
  ModalStepMap m;
  step(1, 0, 0, 0, &m.uu, &m.vu);
  step(0, 1, 0, 0, &m.uv, &m.vv);
  step(0, 0, 1, 0, &m.u0, &m.v0);
  step(0, 0, 0, 1, &m.u1, &m.v1);
  return m;
}

// The exact map for a load that varies linearly over the step (first-order
// hold between p_n and p_{n+1}), from the exponential of the augmented system
// [q, q̇/ω, p/ω², ṗ/ω³] in the dimensionless time ωt (all entries O(1)).
ModalStepMap ModalStep(double omega, double damping, double dt) {
  if (!(omega > 0.0))  // a free mass (no damping either, since c ∝ ω²)
    return {1.0, dt, dt * dt / 3.0, dt * dt / 6.0, 0.0, 1.0, 0.5 * dt, 0.5 * dt};
  const double tau = omega * dt;
  if (tau > kExactStepLimit) return NewmarkModalStep(omega, damping, dt);
  Eigen::Matrix4d a = Eigen::Matrix4d::Zero();
  a(0, 1) = 1.0;
  a(1, 0) = -1.0;
  a(1, 1) = -damping / omega;
  a(1, 2) = 1.0;
  a(2, 3) = 1.0;
  const Eigen::Matrix4d e = (a * tau).exp();
  const double w2 = omega * omega;
  // p/ω² enters column 2; its slope (p_{n+1} − p_n)/(ω³Δt) column 3.
  const double ramp = 1.0 / (w2 * tau);
  return {.uu = e(0, 0),
          .uv = e(0, 1) / omega,
          .u0 = e(0, 2) / w2 - e(0, 3) * ramp,
          .u1 = e(0, 3) * ramp,
          .vu = omega * e(1, 0),
          .vv = e(1, 1),
          .v0 = omega * (e(1, 2) / w2 - e(1, 3) * ramp),
          .v1 = omega * e(1, 3) * ramp};
}

}  // namespace

void TimeSimulatorOptions::Validate() const {
  using namespace option_checks;
  // Half the readers' floor on max_time_step_s (1e-7 s): the stepped sine
  // divides the sample period into whole steps, which lie between half that
  // bound and the bound.
  RequireAtLeast("TimeSimulatorOptions.time_step_s", time_step_s, 5e-8);
  RequireNonNegative("TimeSimulatorOptions.damping_reference_rad_s", damping_reference_rad_s);
  mesh.Validate();
  RequireAtLeast("TimeSimulatorOptions.max_newton_iterations", max_newton_iterations, 1);
}

TimeSimulator::TimeSimulator(const TimeSimulatorModel& model, const SupportLaw& law,
                             const TimeSimulatorOptions& options)
    : fe_beam_(model.beam, model.attachments,
               [&] {
                 // Here, since the mesh is built before the constructor's body.
                 options.Validate();
                 std::vector<double> nodes = model.output_positions_m;
                 nodes.push_back(model.force_position_m);
                 return nodes;
               }(),
               options.mesh),
      law_(law.Clone()),
      time_step_s_(options.time_step_s),
      max_newton_iterations_(options.max_newton_iterations) {
  const int force_dof = model.base_excitation ? FeBeam::kConstrained : fe_beam_.DeflectionDof(model.force_position_m);
  if (!model.base_excitation && force_dof == FeBeam::kConstrained)
    throw std::invalid_argument("time simulator: the force acts at a constrained point (x = 0 or a rigid support)");

  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> modes(fe_beam_.Stiffness(), fe_beam_.Mass());
  if (modes.info() != Eigen::Success) throw NumericalError("time simulator: modal decomposition failed");
  const Eigen::MatrixXd& phi = modes.eigenvectors();  // Φᵀ M Φ = I
  modal_stiffness_ = modes.eigenvalues().array().max(0.0);
  omega_ = modal_stiffness_.sqrt();

  if (options.damping_reference_rad_s > 0.0) {
    damping_reference_rad_s_ = options.damping_reference_rad_s;
  } else {
    damping_reference_rad_s_ = fe_beam_.NaturalFrequencies_rad_s(1, law_->InitialStiffness_Nm_rad()).at(0);
  }
  loss_factor_ = model.beam.loss_factor;
  beta_damping_s_ = loss_factor_ / damping_reference_rad_s_;
  viscous_damping_ = model.beam.rayleigh_mass_1_s + model.beam.rayleigh_stiffness_s * modal_stiffness_;
  const auto& ratios = model.modal_damping_ratios;
  for (double zeta : ratios)
    if (!(zeta >= 0.0 && zeta < 1.0))
      throw std::invalid_argument("time simulator: a modal damping ratio must lie in [0, 1), not " + std::to_string(zeta));
  for (Eigen::Index j = 0; j < omega_.size() && !ratios.empty(); ++j)
    viscous_damping_(j) += 2.0 * ratios[std::min<std::size_t>(j, ratios.size() - 1)] * omega_(j);
  modal_damping_ = beta_damping_s_ * modal_stiffness_ + viscous_damping_;

  if (model.base_excitation) {
    // The modal load per unit of a_b: −Φᵀ·M·r, r the base's rigid translation.
    Eigen::VectorXd translation = Eigen::VectorXd::Zero(fe_beam_.NumDofs());
    for (double x : fe_beam_.node_positions_m()) {
      const int dof = fe_beam_.DeflectionDof(x);
      if (dof != FeBeam::kConstrained) translation(dof) = 1.0;
    }
    force_shape_ = -(phi.transpose() * (fe_beam_.Mass() * translation)).array();
  } else {
    force_shape_ = phi.row(force_dof).transpose().array();
  }
  rotation_shape_ = phi.row(fe_beam_.SupportRotationDof()).transpose().array();
  output_modes_ = Eigen::MatrixXd::Zero(static_cast<int>(model.output_positions_m.size()), phi.cols());
  for (size_t i = 0; i < model.output_positions_m.size(); ++i) {
    const int dof = fe_beam_.DeflectionDof(model.output_positions_m[i]);
    if (dof != FeBeam::kConstrained) output_modes_.row(static_cast<int>(i)) = phi.row(dof);
  }
  UpdateStepMaps();
  Reset(0.0);
}

void TimeSimulator::UpdateStepMaps() {
  const int n = static_cast<int>(omega_.size());
  for (Eigen::ArrayXd* a : {&uu_, &uv_, &u0_, &u1_, &vu_, &vv_, &v0_, &v1_}) a->resize(n);
  for (int j = 0; j < n; ++j) {
    const ModalStepMap m = ModalStep(omega_(j), modal_damping_(j), time_step_s_);
    uu_(j) = m.uu, uv_(j) = m.uv, u0_(j) = m.u0, u1_(j) = m.u1;
    vu_(j) = m.vu, vv_(j) = m.vv, v0_(j) = m.v0, v1_(j) = m.v1;
  }
  moment_flexibility_ = (rotation_shape_.square() * u1_).sum();
  moment_rate_flexibility_ = (rotation_shape_.square() * v1_).sum();
}

void TimeSimulator::MatchLossFactorAt(double omega_rad_s) {
  if (!(omega_rad_s > 0.0)) throw std::invalid_argument("time simulator: the driving frequency must be positive");
  beta_damping_s_ = 0.0;
  for (Eigen::Index j = 0; j < omega_.size(); ++j) {
    const double harmonic = std::max(1.0, std::round(omega_(j) / omega_rad_s));
    modal_damping_(j) = loss_factor_ * modal_stiffness_(j) / (harmonic * omega_rad_s) + viscous_damping_(j);
  }
  UpdateStepMaps();
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

double TimeSimulator::SolveSupport(double theta_predicted, double rate_predicted, double* moment_Nm,
                                   std::vector<double>& law_state_out) const {
  const double g = moment_flexibility_;
  // θ = θ_pred − g·M and θ̇ = θ̇_pred − g_v·M, so θ̇(θ) = θ̇_pred + (g_v/g)·(θ − θ_pred).
  const double rate_per_theta = moment_rate_flexibility_ / moment_flexibility_;
  const double theta_n = state_.theta_rad;
  // r(θ) = θ − θ_pred + g·M_s(θ, θ̇(θ)); r is increasing for any law whose
  // tangents are non-negative, which Newton exploits and bisection relies on.
  auto residual = [&](double theta, double* slope, double* moment) {
    const SupportLawResponse r = law_->Evaluate(theta, rate_predicted + rate_per_theta * (theta - theta_predicted),
                                                state_.law_state, law_state_out);
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
    throw NumericalError("time simulator: the support equation has no solution at t = " +
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
  State& s = state_;
  // Into scratch kept between steps: a step allocates nothing (the
  // allocations cost a third of its time). The expressions are the ones
  // evaluated into new arrays before, so every sample is the same to the
  // last bit.
  // The step with the support's end moment M set to 0; M enters linearly
  // through u1, v1 (the load ramps from its value at t_n to the one at t_n+1).
  load_n_ = force_shape_ * s.force_N - rotation_shape_ * s.support_moment_Nm;
  const Eigen::ArrayXd& u = s.modal_displacement;
  const Eigen::ArrayXd& v = s.modal_velocity;
  u_free_ = uu_ * u + uv_ * v + u0_ * load_n_ + (u1_ * force_shape_) * force_N;
  v_free_ = vu_ * u + vv_ * v + v0_ * load_n_ + (v1_ * force_shape_) * force_N;
  const double theta_free = (rotation_shape_ * u_free_).sum();
  const double rate_free = (rotation_shape_ * v_free_).sum();

  law_state_out_.assign(s.law_state.size(), 0.0);
  double moment_Nm = 0.0;
  const double theta = SolveSupport(theta_free, rate_free, &moment_Nm, law_state_out_);

  s.modal_displacement = u_free_ - (u1_ * rotation_shape_) * moment_Nm;
  s.modal_velocity = v_free_ - (v1_ * rotation_shape_) * moment_Nm;
  s.modal_acceleration = force_shape_ * force_N - rotation_shape_ * moment_Nm - modal_damping_ * s.modal_velocity -
                         modal_stiffness_ * s.modal_displacement;
  s.theta_rate_rad_s = rate_free - moment_rate_flexibility_ * moment_Nm;
  s.theta_rad = theta;
  s.support_moment_Nm = moment_Nm;
  std::swap(s.law_state, law_state_out_);
  s.force_N = force_N;
  s.time_s += time_step_s_;
}

void TimeSimulator::Outputs(Eigen::Ref<Eigen::VectorXd> displacement_m, Eigen::Ref<Eigen::VectorXd> velocity_m_s,
                            Eigen::Ref<Eigen::VectorXd> acceleration_m_s2) const {
  displacement_m.noalias() = output_modes_ * state_.modal_displacement.matrix();
  velocity_m_s.noalias() = output_modes_ * state_.modal_velocity.matrix();
  acceleration_m_s2.noalias() = output_modes_ * state_.modal_acceleration.matrix();
}

}  // namespace beamid::hb
