// The exact linear beam: Euler–Bernoulli, clamped at x = 0, y(L) = 0, with a
// linear rotational spring and dashpot at the support,
//     EI·y''(L) = −(k1·θ + c·θ̇) + M_applied,   θ = y'(L),
// plus the LinearAttachments. No modal truncation: the beam is cut into
// segments at the force, the masses and x = L; each segment is represented by
// its exact dynamic stiffness matrix (built from the Krylov–Duncan transfer
// matrix of w'''' = λ⁴w, λ⁴ = ρAω²/(EI(1+iη))), which stays exact and well
// conditioned from ω = 0 (static) to the high harmonics. The segments are
// assembled like finite elements, so attachments are diagonal additions.
//
// Sign convention (docs/derivation.md): a positive support moment resists a
// positive rotation; the seed's Eq. (3)/(18) has the opposite sign of k1.
// Phasors: a real signal x(t) = Re(X·e^{iωt}) (docs/fourier-convention.md).
#pragma once

#include <complex>
#include <memory>
#include <vector>

#include <Eigen/Core>

#include "hb/beam_properties.h"
#include "hb/linear_attachments.h"

namespace beamid::hb {

using Complex = std::complex<double>;

struct LinearBeamModel {
  BeamProperties beam;
  LinearAttachments attachments;
  // k1 [N·m/rad] and c [N·m·s/rad] of the support; 0 = a pinned end.
  double support_stiffness_Nm_rad = 0.0;
  double support_damping_Nms_rad = 0.0;
};

struct BeamMesh;  // hb/internal/beam_mesh.h
class MatchedModalLoss;  // hb/matched_modal_loss.h

// A complex steady-state deflection shape at one angular frequency, valid at
// every x in [0, L] (evaluated exactly inside each segment).
class BeamDeflection {
 public:
  Complex Displacement_m(double position_m) const;
  Complex Slope_rad(double position_m) const;
  Complex SupportRotation_rad() const;  // θ = y'(L)

 private:
  friend class LinearBeam;
  std::shared_ptr<const BeamMesh> mesh_;
  double omega_rad_s_ = 0.0;
  Eigen::VectorXcd nodal_;              // [y, y'] at every node
  Complex Evaluate(double position_m, int derivative) const;
};

struct LinearBeamOptions {
  // Highest frequency at which results must be exact to ~1e-10 [Hz]. Segments
  // are kept shorter than 12/λ(max) so that cosh(λℓ) stays below ~1e5 and the
  // segment matrices keep their accuracy; above it precision degrades
  // gradually (about one digit per further 2.3 of λℓ).
  double max_frequency_hz = 5000.0;

  // Throws InputError naming the field, its value and the allowed range.
  void Validate() const;
};

class LinearBeam {
 public:
  // force_position_m: where the shaker acts (a node of the segmentation).
  LinearBeam(const LinearBeamModel& model, double force_position_m, const LinearBeamOptions& options = {});

  const LinearBeamModel& model() const { return model_; }
  double force_position_m() const { return force_position_m_; }

  // Undamped natural frequencies [rad/s], the first `count`, counted exactly
  // with the Wittrick–Williams algorithm (no mode is missed).
  std::vector<double> NaturalFrequencies_rad_s(int count) const;
  // Mode shape of mode `index` (0-based), scaled so that max|w| = 1 and
  // w is positive where |w| is largest.
  BeamDeflection ModeShape(int index) const;

  // Steady state under a unit force phasor at the force position.
  BeamDeflection RespondToForce(double omega_rad_s) const;
  // Steady state under a unit moment phasor applied at x = L, acting in the
  // direction of positive θ.
  BeamDeflection RespondToSupportMoment(double omega_rad_s) const;

  // The beam condensed on θ = y'(L), with θ held as the one free boundary
  // quantity and no support spring (k1 and c of the model are ignored): at
  // frequency ω the beam's equilibrium at its end reads
  //     D(ω)·Θ + M_support = B(ω)·F,
  // and the displacement at position x is a_x(ω)·F + b_x(ω)·Θ. This is the
  // linear part of the harmonic balance; M_support is the full support law.
  struct Condensed {
    Complex rotational_stiffness_Nm_rad;   // D
    Complex blocked_moment_per_force_m;    // B [N·m/N]
    Eigen::VectorXcd displacement_per_force_m_N;    // a_x
    Eigen::VectorXcd displacement_per_rotation_m;   // b_x
  };
  Condensed CondenseOnSupportRotation(double omega_rad_s,
                                      const std::vector<double>& output_positions_m) const;

  // The beam's modal loss factor (BeamProperties::modal_loss_factor), which
  // depends on the drive's fundamental as well as on the frequency: applied
  // by ComputeLinearHarmonics (hb/harmonic_balance.h) to what
  // CondenseOnSupportRotation returns; nullptr when η_m = 0. The other
  // members of this class leave it out.
  const MatchedModalLoss* matched_modal_loss() const { return matched_modal_loss_.get(); }

 private:
  LinearBeamModel model_;
  double force_position_m_;
  std::shared_ptr<const BeamMesh> mesh_;
  std::shared_ptr<const MatchedModalLoss> matched_modal_loss_;
};

}  // namespace beamid::hb
