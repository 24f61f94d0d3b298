// The beam's loss factor matched per mode at the harmonic that drives it: the
// structural damping of time-domain codes that integrate a loss factor η_m
// (hb/time_simulator.h) and the constant modal damping ratio (ζ ≈ η_m/2) of
// modal analysis. Mode j of the beam with θ = y'(L) free and no support law
// gets the viscous modal damping
//     c_j = η_m·ω_j²/(k_j·ω),   k_j = max(1, round(ω_j/ω)),
// k_j·ω the harmonic of the drive ω nearest ω_j, so that at harmonic k
// (Ω = kω) its modal stiffness is ω_j²(1 + iη_m·k/k_j): exactly E(1 + iη_m)
// at its driving harmonic (the fundamental for mode 1, the 3rd for mode 2 of
// the paper's beam), less below it, more above. A loss factor EI(1 + iη)
// dissipates as η in every mode at every harmonic instead; the two laws split
// the beam's loss and the support's c differently.
//
// The exact beam has no modes to damp, so the law enters as a modal correction
// of its receptances between θ, the force point and the outputs:
//     H_ab(Ω) += Σ_j φ_j(a)·φ_j(b)·[1/(d_j + iη_m·ω_j²·k/k_j) − 1/d_j],
//     d_j = ω_j²(1 + iη + iβΩ) − Ω² + iαΩ   (the beam's other damping, taken
//                                             as classical),
// over the modes below LinearBeamOptions::max_frequency_hz, 5 kHz at least
// (mode j's share of the loss at harmonic k is η_m·kω/ω_j of its
// quasi-static flexibility, which falls like 1/j²: together they fall like
// 1/j⁴; within 5e-4 of every mode's sum up to the 5th harmonic of the
// paper's beam, tests/hb/matched_modal_loss_test.cc). The modes
// are mass-normalised from the residues of the receptances at θ:
//     φ_j(x)·φ_j'(L) = lim (ω_j² − Ω²)·H_xθ(Ω),
// a central difference at Ω² = ω_j²(1 ∓ ε) (ω_j is known to 1e-13).
// The corrected receptances are condensed on θ again without inverting D
// (which vanishes at the θ-free natural frequencies, inside the test's band):
//     D' = D/(1 + D·S_θθ),   B' = (B + D·S_θF)/(1 + D·S_θθ),
//     b' = (b + D·S_xθ)/(1 + D·S_θθ),
//     a' = a + S_xF + (b·B·S_θθ − b·S_θF − B·S_xθ − D·S_xθ·S_θF)/(1 + D·S_θθ),
// S_ab the sums above (hb/linear_beam.h: H_θθ = 1/D, H_θF = B/D,
// H_xθ = b/D, H_xF = a + b·B/D).
//
// The modes depend on the undamped beam alone, and a fit rebuilds the beam
// at every change of η_m (and at each of its difference quotients): they are
// computed once per undamped beam and shared (a diagnosis of the paper's
// set-up took 13 times as long with η_m as with η before).
#pragma once

#include <memory>
#include <vector>

#include <Eigen/Core>

#include "hb/linear_beam.h"

namespace beamid::hb {

class MatchedModalLoss {
 public:
  // The undamped beam's modes: natural frequencies and, per mode, the
  // θ-free beam's response to a unit moment at Ω² = ω_j²(1 ∓ ε), the scale
  // that turns their difference into φ_j, and φ_j'(L).
  struct Modes {
    std::vector<double> omega_rad_s;
    std::vector<BeamDeflection> below, above;
    std::vector<double> scale, rotation;
  };

  // The modes of `model`'s beam (attachments kept; support spring, dashpot
  // and every damping dropped) below max(options.max_frequency_hz, 5 kHz).
  MatchedModalLoss(const LinearBeamModel& model, double force_position_m, const LinearBeamOptions& options);

  int num_modes() const { return static_cast<int>(modes_->omega_rad_s.size()); }
  const std::vector<double>& natural_frequencies_rad_s() const { return modes_->omega_rad_s; }

  // Mass-normalised mode values, one row per mode.
  struct ModeValues {
    Eigen::VectorXd rotation;      // φ_j'(L)
    Eigen::VectorXd at_force;      // φ_j(x_F)
    Eigen::MatrixXd at_positions;  // φ_j(x), modes × positions
  };
  ModeValues At(const std::vector<double>& positions_m) const;

  // Adds the law (η_m = the model's modal_loss_factor) to `condensed`, the
  // beam condensed on θ at Ω = harmonic·ω (harmonic ≥ 1).
  void Correct(const ModeValues& modes, double omega_rad_s, int harmonic, LinearBeam::Condensed* condensed) const;

 private:
  double modal_loss_factor_ = 0.0;
  double loss_factor_ = 0.0;
  double rayleigh_mass_1_s_ = 0.0;
  double rayleigh_stiffness_s_ = 0.0;
  double force_position_m_ = 0.0;
  std::shared_ptr<const Modes> modes_;
};

}  // namespace beamid::hb
