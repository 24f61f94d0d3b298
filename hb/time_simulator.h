// Time-domain simulator of the beam on its nonlinear support: the FeBeam
// model (hb/fe_beam.h) integrated in time,
//     M·q̈ + C·q̇ + K·q = f_F(t)·e_F − M_s(θ, θ̇, history)·e_θ,   θ = y'(L),
// where f_F is the shaker force at its node and M_s the support law's moment
// (hb/support_law.h: it acts against θ, EI·y''(L) = −M_s); with base
// excitation f_F·e_F is replaced by −M·r·a_b (TimeSimulatorModel).
//
// Structural damping is classical. By default it is stiffness proportional,
// C = (η/ω_ref)·K: a beam vibrating at ω_ref dissipates exactly as the complex
// modulus E(1 + iη) of hb/beam_properties.h; ω_ref defaults to the first
// natural frequency with the support law's initial stiffness, so mode 1 has a
// damping ratio ≈ η/2. Such damping grows with frequency (3η at 3·ω_ref), so a
// steady state driven at ω calls MatchLossFactorAt(ω): mode j then gets
//     c_j = η·ω_j² / (k_j·ω),   k_j·ω the harmonic of ω nearest ω_j,
// and dissipates exactly like E(1 + iη) at the harmonic that drives it (the
// fundamental for mode 1, the 3rd for mode 2 of the paper's beam, its own
// frequency for a high mode): the real beam's frequency-independent loss.
// Two other laws add to it, to test fits that assume the loss factor: the
// beam's Rayleigh damping (BeamProperties' α, β: c_j += α + β·ω_j², the same
// C = α·M + β·K as the exact beam's ρA(ω² − iαω), EI(1 + iβω)) and modal
// damping ratios (c_j += 2ζ_j·ω_j; the last ratio given holds for the higher
// modes). The modes are those of the beam without the support law (whose
// moment acts as a load), so mode 1 here has a free rotation at x = L.
//
// K, M, C are linear and C is classical, so the beam is integrated in its
// mass-normalised modes of (K, M), every mode kept. Each mode with ωΔt ≤ 1
// is stepped EXACTLY for a load that varies linearly between the step's ends
// (first-order hold; the one-step map is the exponential of the mode's
// augmented state matrix), so the modes the test drives have no period error
// at any Δt (Newmark's average acceleration, used for them before, lowered
// their frequencies by ≈ (ωΔt)²/12, which a fit resolves); what remains is
// the hold of the load, an amplitude factor ≈ 1 − (ωΔt)²/12 on the force and
// on the support's moment, with no phase error. Higher modes, which respond
// quasi-statically, keep Newmark's average acceleration (unconditionally
// stable, no numerical damping): stepped exactly, a mode near 2π/Δt would
// resonate with the images of the held load. The support law couples the modes through the single DOF θ; it is
// implicit in the moment at the step's end: θ = θ_pred − g·M and
// θ̇ = θ̇_pred − g_v·M, so each step solves the scalar equation
// θ + g·M_s(θ, θ̇(θ)) = θ_pred by a safeguarded Newton iteration with the
// law's consistent tangents. The law's internal state (e.g. the Jenkins
// slider) is committed only after convergence.
#pragma once

#include <memory>
#include <vector>

#include <Eigen/Core>

#include "hb/beam_properties.h"
#include "hb/fe_beam.h"
#include "hb/linear_attachments.h"
#include "hb/support_law.h"

namespace beamid::hb {

struct TimeSimulatorModel {
  BeamProperties beam;  // true beam; loss_factor is η of the structural damping
  LinearAttachments attachments;
  double force_position_m = 0.570;
  // Base excitation: the clamp and the support translate together with the
  // acceleration a_b(t). The beam is then integrated in coordinates relative
  // to them (the springs and the support law see relative motion) under the
  // inertial load −M·r·a_b, r = 1 on every deflection DOF (the beam's ρA and
  // every point mass); the scalar input of Reset and Advance (the "force")
  // is then a_b [m/s²], and force_position_m is not used. Outputs and state
  // are relative to the base.
  bool base_excitation = false;
  // ζ_j of modal damping, mode 1 first; empty = none.
  std::vector<double> modal_damping_ratios;
  // Where deflection, velocity and acceleration are reported (become nodes).
  std::vector<double> output_positions_m;
};

struct TimeSimulatorOptions {
  // Δt [s]. The load's linear hold scales a harmonic at ω by ≈ 1 − (ωΔt)²/12:
  // 4e-6 at 54 Hz and 1e-4 at 270 Hz for the default; frequencies are exact.
  double time_step_s = 1.0 / 51200.0;
  // ω_ref [rad/s] of the stiffness-proportional damping; 0 = first natural
  // frequency of the beam with the law's initial stiffness at x = L.
  double damping_reference_rad_s = 0.0;
  FeBeamOptions mesh;
  int max_newton_iterations = 50;

  // Throws InputError naming the field, its value and the allowed range.
  void Validate() const;
};

class TimeSimulator {
 public:
  // Everything that evolves in time; copy it to branch a simulation.
  struct State {
    Eigen::ArrayXd modal_displacement, modal_velocity, modal_acceleration;
    std::vector<double> law_state;
    double theta_rad = 0.0, theta_rate_rad_s = 0.0, support_moment_Nm = 0.0;
    double force_N = 0.0;
    double time_s = 0.0;
  };

  // Throws std::invalid_argument for an unphysical model (e.g. the force at a
  // constrained point).
  TimeSimulator(const TimeSimulatorModel& model, const SupportLaw& law, const TimeSimulatorOptions& options = {});

  // Modal damping that equals the hysteretic E(1 + iη) at the harmonic of ω
  // nearest each mode (see above), for a steady state driven at ω [rad/s].
  void MatchLossFactorAt(double omega_rad_s);

  // Rest (zero deflection and law state) at time 0 with the given force acting,
  // so the initial acceleration is consistent.
  void Reset(double force_N = 0.0);
  // One step of Δt; force_N is the force at the end of the step. Throws
  // std::runtime_error if the support equation cannot be solved.
  void Advance(double force_N);

  const State& state() const { return state_; }
  void set_state(const State& state) { state_ = state; }
  double time_s() const { return state_.time_s; }
  double time_step_s() const { return time_step_s_; }

  int NumOutputs() const { return static_cast<int>(output_modes_.rows()); }
  // Deflection [m], velocity [m/s], acceleration [m/s²] at every output
  // position, in the order given in the model.
  void Outputs(Eigen::Ref<Eigen::VectorXd> displacement_m, Eigen::Ref<Eigen::VectorXd> velocity_m_s,
               Eigen::Ref<Eigen::VectorXd> acceleration_m_s2) const;
  double SupportRotation_rad() const { return state_.theta_rad; }
  double SupportMoment_Nm() const { return state_.support_moment_Nm; }

  const FeBeam& fe_beam() const { return fe_beam_; }
  // Natural frequencies [rad/s] of the FE model without the support law.
  const Eigen::ArrayXd& modal_frequencies_rad_s() const { return omega_; }
  double damping_reference_rad_s() const { return damping_reference_rad_s_; }
  // β of C = β·K [s]; 0 after MatchLossFactorAt.
  double stiffness_proportional_damping_s() const { return beta_damping_s_; }

 private:
  void UpdateStepMaps();
  double SolveSupport(double theta_predicted, double rate_predicted, double* moment_Nm,
                      std::vector<double>& law_state_out) const;

  FeBeam fe_beam_;
  std::unique_ptr<SupportLaw> law_;
  double time_step_s_;
  int max_newton_iterations_;
  double damping_reference_rad_s_ = 0.0;
  double beta_damping_s_ = 0.0;
  double loss_factor_ = 0.0;

  Eigen::ArrayXd omega_;           // ω_j
  Eigen::ArrayXd modal_damping_;   // c_j (mass-normalised) [1/s]
  Eigen::ArrayXd viscous_damping_; // its Rayleigh and modal part [1/s]
  Eigen::ArrayXd modal_stiffness_; // ω_j²
  // Exact one-step map of each mode: q' = uu·q + uv·q̇ + u0·p_n + u1·p_n+1,
  // q̇' = vu·q + vv·q̇ + v0·p_n + v1·p_n+1 (p the modal load).
  Eigen::ArrayXd uu_, uv_, u0_, u1_, vu_, vv_, v0_, v1_;
  Eigen::ArrayXd force_shape_;     // φ_j at the force DOF
  Eigen::ArrayXd rotation_shape_;  // φ_j at the θ DOF
  Eigen::MatrixXd output_modes_;   // outputs × modes
  double moment_flexibility_ = 0.0;       // g = Σ φ_θj²·u1_j [rad/(N·m)]
  double moment_rate_flexibility_ = 0.0;  // g_v = Σ φ_θj²·v1_j [rad/(N·m·s)]
  State state_;
  // Advance's scratch: the modal load at t_n, the step without the support's
  // moment, and the law's state after the step.
  Eigen::ArrayXd load_n_, u_free_, v_free_;
  std::vector<double> law_state_out_;
};

}  // namespace beamid::hb
