// The seed's multiple-scales model of the first mode, corrected and
// generalised to a point force (docs/derivation.md, which numbers every
// equation against the seed and lists its typos).
//
// Beam: EI·y'''' + ρA·ÿ = F(t)·δ(x − x_F); y(0) = y'(0) = 0, y(L) = 0 and
// EI·y''(L) = −M with M = K1·θ + K2·θ² + K3·θ³ + C·θ̇, θ = y'(L). Ordering
// K2 ~ ε; K3, C, F ~ ε²; Ω = ω0 + ε²σ. With the modal phasor U (first mode w,
// max|w| = 1, so y ≈ Re(U·e^{iΩt})·w(x) + …, docs/fourier-convention.md) the
// solvability condition (corrected Eq. 40) is the complex scalar equation
//     m_eff·(ω0² − Ω²)·U = F1·w(x_F) − w'(L)·M1(U, Ω),     m_eff = ρA·∫w² dx,
// where M1 is the first-harmonic phasor of K2·θ² + K3·θ³ + C·θ̇. Its
// nonlinear part is evaluated on the rotation up to order ε:
//     θ0 = U·w'(L),  θ_static = −K2·|θ0|²·G(0)/2,  θ_2 = −K2·θ0²·G(2Ω)/2,
//     N1 = ¾·K3·|θ0|²·θ0 + 2·K2·(θ0·θ_static + conj(θ0)·θ_2/2),
// G(Ω) = G_θM(Ω) the end rotation per end moment of the plain beam with K1
// (in the generalised form G(2Ω) includes the damper). The seed's form (kNatural) is M1 = iω0·C·θ0 + N1. The
// generalised form (kExcitation, default) keeps the linear support exact:
// the damper also acts on the rotation outside the first mode, i.e. on the
// rotation θ_F = F1·G_rest,θF(Ω) forced directly by the shaker (formally
// O(ε²) smaller, but 8 % of θ0 at 0.95·ω0 with the shaker 3 cm from the
// support) and on the non-resonant rotation −M1·G_rest,θM(Ω) of the
// support moment itself. Solving that linear relation for θ gives
//     M1 = d·(θ0 + θ_F) + (1 − d·G_rest,θM)·N1,   d = iΩ·C/(1 + iΩ·C·G_rest,θM),
// which makes the model exact in the linear limit (K2 = K3 = 0) at every Ω.
// With a = |U| and f = F1·w(x_F) − w'(L)·d·θ_F the amplitude–frequency
// relation is a cubic in a² with one or three positive roots:
//     |m_eff·(ω0² − Ω²) + d·w'(L)² − (1 − d·G_rest,θM)·Γ·a²/4|·a = |f|,
//     Γ(Ω) = [2·K2²·(2·G(0) + G(2Ω)) − 3·K3]·w'(L)⁴          [N/m³].
// The backbone (C = 0, F = 0) is Ω² = ω0² − Γ(Ω)·a²/(4·m_eff). K3 > 0
// hardens; K2 always softens while 2·G(0) + G(2Ω) > 0 (the seed omits the
// static term G(0), Eq. 23).
//
// Only the force's first harmonic F1 enters (higher force harmonics are
// outside the ordering). The beam's loss factor η enters the resonant modal
// term only, as the modal stiffness m_eff·ω0² + iη·EI·∫w''² dx; the
// non-resonant receptances are undamped.
#pragma once

#include <complex>
#include <vector>

#include "hb/beam_properties.h"
#include "hb/closed_form_beam.h"
#include "hb/support_law.h"

namespace beamid::hb {

using Complex = std::complex<double>;

// Where the harmonic receptances and the damping moment are evaluated.
enum class MultipleScalesHarmonicFrequency {
  // Generalised (default): at Ω, 2Ω, 3Ω and iΩ·C, detuning ω0² − Ω². Exact
  // in the linear limit at any Ω.
  kExcitation,
  // The seed's strict first-order form: at ω0, 2ω0 (λ√2), 3ω0 (λ√3) and
  // iω0·C, detuning 2ω0·(ω0 − Ω). Agrees with kExcitation to O(ε²).
  kNatural,
};

struct MultipleScalesOptions {
  MultipleScalesHarmonicFrequency harmonic_frequency = MultipleScalesHarmonicFrequency::kExcitation;

  // Throws InputError when harmonic_frequency is none of the enumerators
  // (a value cast from a number read elsewhere).
  void Validate() const;
};

class MultipleScalesModel {
 public:
  using HarmonicFrequency = MultipleScalesHarmonicFrequency;
  using Options = MultipleScalesOptions;

  // Displacement phasors at one position [m]: h0 the mean, h1…h3 the
  // harmonics (x(t) = h0 + Σ Re(h_k·e^{ikΩt})).
  struct Harmonics {
    double h0_m = 0.0;
    Complex h1_m, h2_m, h3_m;
  };
  // The steady states at one excitation frequency: one or three modal
  // phasors U [m], ascending in |U|.
  struct SweepPoint {
    double omega_rad_s = 0.0;
    std::vector<Complex> modal_phasors_m;
  };

  // The model at one excitation (Ω, F1) and a list of positions: everything
  // that does not depend on U evaluated once (receptances, the linear
  // coupling), so that the solvability residual and the harmonics are cheap
  // polynomials in U and Ū. The model's own SolvabilityResidual_N and
  // Response evaluate through it; an identification, which needs them for
  // many U at a fixed excitation, keeps it.
  class Excitation {
   public:
    Complex SolvabilityResidual_N(Complex modal_phasor_m) const;     // see the model's
    Complex SupportMomentFirstHarmonic_Nm(Complex modal_phasor_m) const;
    Complex FirstHarmonicRotation_rad(Complex modal_phasor_m) const;
    Harmonics Response(int position_index, Complex modal_phasor_m) const;  // positions_m[position_index]

   private:
    friend class MultipleScalesModel;
    Complex NonlinearMoment_Nm(Complex theta0_rad) const;  // N1
    struct AtPosition {
      double mode = 0.0;              // w(x)
      double rest_force_m_N = 0.0;    // G_rest(x; x_F, Ω)
      double rest_moment_m_Nm = 0.0;  // G_rest,M(x; Ω)
      double static_m_Nm = 0.0;       // G_xM(x, 0)
      Complex second_m_Nm, third_m_Nm;  // G_xM(x, 2Ω), G_xM(x, 3Ω) with the damper
    };
    double k2_ = 0.0, k3_ = 0.0, slope_per_m_ = 0.0, static_compliance_rad_Nm_ = 0.0;
    Complex force_phasor_N_, modal_stiffness_N_m_, modal_force_N_;
    Complex damping_Nm_rad_, nonlinear_factor_, forced_rotation_rad_;
    Complex second_compliance_rad_Nm_;  // G(2Ω), with the damper in the generalised form
    double rest_rotation_rad_Nm_ = 0.0;  // G_rest,θM(Ω) (0 in the seed's form: θ1 = θ0)
    std::vector<AtPosition> positions_;
  };

  // Throws std::invalid_argument for a non-physical beam, K1 < 0, C < 0, a
  // non-finite coefficient or a force position outside [0, L].
  MultipleScalesModel(const BeamProperties& beam, const PolynomialSupportLaw::Coefficients& support,
                      double force_position_m, const Options& options = {});

  double NaturalFrequency_rad_s() const { return omega0_rad_s_; }          // ω0
  double ModalMass_kg() const { return modal_mass_kg_; }                   // m_eff
  double ModeShape(double position_m) const { return mode_.Value(position_m); }  // w(x)
  double SupportSlope_per_m() const { return support_slope_per_m_; }     // w'(L)
  const ClosedFormBeam& linear_beam() const { return closed_form_; }

  // Γ(Ω) [N/m³] of the amplitude–frequency relation, undamped (the backbone's;
  // Solve() uses G(2Ω) with the damper in the generalised form).
  double CubicCoefficient_N_m3(double omega_rad_s) const;
  // M1 [N·m]: first harmonic of the nonlinear and damping support moment.
  Complex SupportMomentFirstHarmonic_Nm(Complex modal_phasor_m, double omega_rad_s, Complex force_phasor_N) const;
  // θ_F = F1·G_rest,θF(Ω) [rad]: the non-resonant end rotation forced directly
  // by F1 (large when x_F is near the support); 0 in the seed's form.
  Complex ForcedRotation_rad(double omega_rad_s, Complex force_phasor_N) const;
  // m_eff·(ω0² − Ω²)·U − F1·w(x_F) + w'(L)·M1 [N]; zero on a solution.
  Complex SolvabilityResidual_N(Complex modal_phasor_m, double omega_rad_s, Complex force_phasor_N) const;

  // θ1 [rad]: the first harmonic of the support rotation that drives the
  // 0th, 2nd and 3rd harmonics: θ0 + θ_F − M1·G_rest,θM (generalised form;
  // y'(L) of h1), θ0 = U·w'(L) (seed's form).
  Complex FirstHarmonicRotation_rad(Complex modal_phasor_m, double omega_rad_s, Complex force_phasor_N) const;

  // Throws std::invalid_argument for a position outside the beam and
  // std::runtime_error at an internal resonance (2Ω or 3Ω a natural frequency).
  Excitation AtExcitation(double omega_rad_s, Complex force_phasor_N, const std::vector<double>& positions_m = {}) const;

  // All steady states U at Ω (the roots of the amplitude–frequency relation,
  // with their phase), ascending in |U|.
  std::vector<Complex> Solve(double omega_rad_s, Complex force_phasor_N) const;
  std::vector<SweepPoint> Sweep(const std::vector<double>& omegas_rad_s, Complex force_phasor_N) const;

  // Displacement harmonics at position_m for the steady state U:
  //   h0 = −(K2/2)·|θ1|²·G_xM(x, 0)
  //   h1 = U·w(x) + F1·G_rest(x; x_F, Ω) − M1·G_rest,M(x; Ω)
  //   h2 = −(K2/2)·θ1²·G_xM(x, 2Ω)
  //   h3 = −(θ1³/4)·(K3 − 2·K2²·G(2Ω))·G_xM(x, 3Ω)
  // G_xM: displacement per end moment; G_rest: the exact receptance minus the
  // first mode's own term w(x)·w(·)/(m_eff·(ω0² − Ω²)) (the seed's N(x)).
  // Seed's form: θ1 = θ0 = U·w'(L), undamped receptances at kω0. Generalised
  // form: θ1 = θ0 + θ_F − M1·G_rest,θM (the whole first-harmonic rotation) and
  // the receptances at 2Ω, 3Ω include the damper (at 3Ω, 3Ω·C is a third of
  // K1 for C = 0.05 N·m·s/rad).
  Harmonics Response(double position_m, Complex modal_phasor_m, double omega_rad_s,
                     Complex force_phasor_N) const;

  // Undamped, unforced: Ω(a) with Ω² = ω0² − Γ(Ω)·a²/(4·m_eff), a = |U| [m].
  // Throws std::runtime_error where no real Ω exists (amplitude far outside
  // the model's range) or the fixed point does not converge.
  double Backbone_rad_s(double amplitude_m) const;

 private:
  double HarmonicBase_rad_s(double omega_rad_s) const;
  Complex ModalDynamicStiffness_N_m(double omega_rad_s) const;  // m_eff·(ω0² − Ω²) + iη…
  double DisplacementPerEndMoment_m_Nm(double position_m, double omega_rad_s) const;
  // Exact receptance minus the first mode's term; smooth through ω0.
  double NonResonantForce_m_N(double position_m, double omega_rad_s, int derivative = 0) const;
  double NonResonantMoment_m_Nm(double position_m, double omega_rad_s, int derivative = 0) const;
  // The linear support terms of the first harmonic (see the file comment).
  struct LinearCoupling {
    Complex damping_Nm_rad;         // d = iΩ·C/(1 + iΩ·C·G_rest,θM)
    Complex nonlinear_factor;       // 1 − d·G_rest,θM
    Complex forced_rotation_rad;    // θ_F
  };
  LinearCoupling Coupling(double omega_rad_s, Complex force_phasor_N) const;
  // 1/(1 + iω·C·G_θM(ω)): turns an undamped end-moment receptance at a
  // harmonic frequency ω into the one with the damper (1 in the seed's form).
  Complex DamperFactor(double harmonic_omega_rad_s) const;
  // G_θM at 2Ω with the damper (generalised form) or at 2ω0 (seed's form).
  Complex SecondHarmonicCompliance_rad_Nm(double omega_rad_s) const;

  BeamProperties beam_;
  PolynomialSupportLaw::Coefficients support_;
  double force_position_m_;
  Options options_;
  ClosedFormBeam closed_form_;
  ClosedFormShape mode_;
  double omega0_rad_s_ = 0.0;
  double modal_mass_kg_ = 0.0;
  double modal_loss_stiffness_N_m_ = 0.0;  // η·EI·∫w''²
  double support_slope_per_m_ = 0.0;
  double mode_at_force_ = 0.0;             // w(x_F)
  double static_rotation_per_moment_rad_Nm_ = 0.0;  // G(0)
};

}  // namespace beamid::hb
