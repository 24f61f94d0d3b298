// Closed-form solutions of the plain beam of the seed (no attachments, no
// damping): Euler–Bernoulli, clamped at x = 0, y(L) = 0, and a linear
// rotational spring K1 at x = L. Per EI, k1 = K1/EI [1/m], and every
// harmonic solution of
//     y'''' = μ⁴·y,   μ⁴ = ρA·ω²/EI,                         (seed Eq. 16)
//     y(0) = y'(0) = 0,  y(L) = 0,  y''(L) + k1·y'(L) = r_M    (corrected Eq. 17/18)
// is y = C1(sin μx − sinh μx) + C2(cos μx − cosh μx) [+ a point-force term].
// With r_M = 0 the 2×2 system in (C1, C2) is singular at the roots of
//     k1·(1 − cos μL·cosh μL) + μ·(sin μL·cosh μL − cos μL·sinh μL) = 0
// (corrected Eq. 19/20: "+μ", the seed's "−λ" belongs to its wrong-signed
// boundary condition). Limits: k1 = 0 gives tan μL = tanh μL (μ₁L = 3.92660),
// k1 → ∞ gives cos μL·cosh μL = 1 (μ₁L = 4.73004).
//
// This file is independent of LinearBeam (a segmented dynamic-stiffness
// model) on purpose: tests compare the two. The functions evaluate the
// hyperbolic terms as decaying exponentials, so they neither overflow nor
// cancel for μL of the first modes and their harmonics (tested to μL ≈ 30).
// docs/derivation.md gives the derivation and the seed's typos.
#pragma once

#include <array>
#include <vector>

#include "hb/beam_properties.h"

namespace beamid::hb {

// The characteristic function divided by cosh(μL), in the dimensionless
// lambda_l = μL and stiffness_l = k1·L = K1·L/EI; stiffness_l = +∞ gives the
// clamped–clamped function 1/cosh μL − cos μL.
double CharacteristicFunction(double lambda_l, double stiffness_l);

// The first `count` roots μₙL of CharacteristicFunction, ascending. Each lies
// between the pinned and the clamped root of the same order (interlacing), which
// brackets it; the root is then refined by bisection to machine precision.
// Throws std::invalid_argument if stiffness_l < 0 or is NaN, or count < 1.
std::vector<double> CharacteristicRoots(double stiffness_l, int count);

// A harmonic deflection shape of the plain beam, evaluated exactly at any x.
// Scale is that of the problem it solves (see ClosedFormBeam).
class ClosedFormShape {
 public:
  // d^k y/dx^k at position_m, k = derivative in 0…4.
  double Value(double position_m, int derivative = 0) const;
  // ∫₀ᴸ (d^k y/dx^k)² dx by composite Gauss–Legendre quadrature.
  double SquareIntegral(int derivative = 0) const;

 private:
  friend class ClosedFormBeam;
  enum class Basis { kStatic, kSeries, kExponential };
  static Basis ChooseBasis(double wavenumber_per_m, double length_m);
  // d^k/dx^k of the two basis functions that satisfy y(0) = y'(0) = 0.
  std::array<double, 2> Basis2(double position_m, int derivative) const;
  double JumpTerm(double z_m, int derivative) const;

  Basis basis_ = Basis::kStatic;
  double length_m_ = 0.0;
  double wavenumber_per_m_ = 0.0;  // μ
  double coefficients_[2] = {0.0, 0.0};
  // Point-force term: jump_weight·g(x − x_F) for x > x_F, where g is the
  // free-space solution with g'''(0⁺) = 1 (a unit jump of the shear).
  double jump_position_m_ = 0.0;
  double jump_weight_ = 0.0;
};

class ClosedFormBeam {
 public:
  // support_stiffness_Nm_rad = K1 ≥ 0 (finite). The beam's loss factor is
  // ignored: these are the undamped closed forms.
  ClosedFormBeam(const BeamProperties& beam, double support_stiffness_Nm_rad);

  const BeamProperties& beam() const { return beam_; }
  double support_stiffness_Nm_rad() const { return support_stiffness_Nm_rad_; }

  // μ = (ρA·ω²/EI)^¼ [1/m].
  double Wavenumber_per_m(double omega_rad_s) const;
  // ωₙ = (μₙL)²/L²·√(EI/ρA), the first `count`, ascending.
  std::vector<double> NaturalFrequencies_rad_s(int count) const;
  // Mode `index` (0-based), scaled like LinearBeam::ModeShape: max|w| = 1 and
  // w > 0 where |w| is largest.
  ClosedFormShape ModeShape(int index) const;

  // P(x; ω): the seed's Q(x, μ) with our normalisation, the solution with
  // P''(L) + k1·P'(L) = 1. It is EI × the displacement per unit moment
  // applied at x = L in the direction of positive θ = y'(L) (K1 spring in
  // place, undamped). ω = 0 gives the static cubic (x³ − L·x²)/(L·(4 + k1·L)).
  ClosedFormShape EndMomentShape(double omega_rad_s) const;
  // EI × the displacement per unit transverse force at force_position_m.
  ClosedFormShape PointForceShape(double omega_rad_s, double force_position_m) const;

  // G_θM(ω) = P'(L; ω)/EI [rad/(N·m)]: end rotation per unit end moment;
  // non-finite at a natural frequency.
  double RotationPerEndMoment_rad_Nm(double omega_rad_s) const;

 private:
  // The shape with y''(L) + k1·y'(L) = moment_rhs and, if force_weight ≠ 0,
  // a shear jump force_weight at force_position_m.
  ClosedFormShape Solve(double omega_rad_s, double moment_rhs, double force_position_m,
                        double force_weight) const;
  double StiffnessPerBendingStiffness_per_m() const;  // k1 = K1/EI

  BeamProperties beam_;
  double support_stiffness_Nm_rad_;
};

}  // namespace beamid::hb
