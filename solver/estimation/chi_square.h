// Tails of the χ² distribution, for testing sums of squared standardised
// residuals: P(χ²(ν) ≥ x) = Q(ν/2, x/2), the regularized upper incomplete
// gamma function, evaluated by its series (x < a + 1) or Lentz's continued
// fraction (otherwise), both to ~1e-14 relative (Numerical Recipes §6.2).
#pragma once

namespace beamid::solver {

// χ²(1) at 99 %: the gap in χ² (in units of the reduced χ² when that
// exceeds 1) beyond which the data decide between two fits.
inline constexpr double kDecisiveChiSquare = 6.635;

// Q(a, x) = Γ(a, x)/Γ(a), a > 0, x ≥ 0. Throws std::invalid_argument otherwise.
double RegularizedUpperGamma(double a, double x);

// P(χ²(dof) ≥ x); 1 for x ≤ 0, and 1 for dof = 0 (nothing tested).
double ChiSquareUpperTail(double x, double dof);

// The x with P(χ²(dof) ≥ x) = upper_tail (bisection on the tail, to 1e-12
// relative), dof > 0 and 0 < upper_tail < 1. Throws std::invalid_argument
// otherwise.
double ChiSquareUpperQuantile(double upper_tail, double dof);

}  // namespace beamid::solver
