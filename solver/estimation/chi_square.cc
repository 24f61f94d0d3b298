#include "solver/estimation/chi_square.h"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace beamid::solver {

namespace {

constexpr int kMaxIterations = 1000;
constexpr double kEpsilon = 1e-15;

// P(a, x) by its series Σ xⁿ/(a(a+1)…(a+n)), converging fast for x < a + 1.
double LowerSeries(double a, double x) {
  double term = 1.0 / a, sum = term;
  for (int n = 1; n < kMaxIterations; ++n) {
    term *= x / (a + n);
    sum += term;
    if (std::abs(term) < std::abs(sum) * kEpsilon) break;
  }
  return sum * std::exp(-x + a * std::log(x) - std::lgamma(a));
}

// Q(a, x) by the continued fraction (modified Lentz), for x ≥ a + 1.
double UpperContinuedFraction(double a, double x) {
  constexpr double kTiny = std::numeric_limits<double>::min() / kEpsilon;
  double b = x + 1.0 - a, c = 1.0 / kTiny, d = 1.0 / b, h = d;
  for (int i = 1; i < kMaxIterations; ++i) {
    const double an = -i * (i - a);
    b += 2.0;
    d = an * d + b;
    if (std::abs(d) < kTiny) d = kTiny;
    c = b + an / c;
    if (std::abs(c) < kTiny) c = kTiny;
    d = 1.0 / d;
    const double delta = d * c;
    h *= delta;
    if (std::abs(delta - 1.0) < kEpsilon) break;
  }
  return std::exp(-x + a * std::log(x) - std::lgamma(a)) * h;
}

}  // namespace

double RegularizedUpperGamma(double a, double x) {
  if (!(a > 0.0) || !(x >= 0.0)) {
    throw std::invalid_argument("RegularizedUpperGamma: need a > 0 and x >= 0, got a = " + std::to_string(a) +
                                ", x = " + std::to_string(x));
  }
  if (x == 0.0) return 1.0;
  if (x < a + 1.0) return 1.0 - LowerSeries(a, x);
  return UpperContinuedFraction(a, x);
}

double ChiSquareUpperTail(double x, double dof) {
  if (dof <= 0.0 || x <= 0.0) return 1.0;
  return RegularizedUpperGamma(0.5 * dof, 0.5 * x);
}

double ChiSquareUpperQuantile(double upper_tail, double dof) {
  if (!(dof > 0.0) || !(upper_tail > 0.0 && upper_tail < 1.0)) {
    throw std::invalid_argument("ChiSquareUpperQuantile: need dof > 0 and 0 < upper_tail < 1, got dof = " +
                                std::to_string(dof) + ", upper_tail = " + std::to_string(upper_tail));
  }
  double low = 0.0, high = dof + 10.0 * std::sqrt(2.0 * dof) + 10.0;
  while (ChiSquareUpperTail(high, dof) > upper_tail) high *= 2.0;
  for (int i = 0; i < kMaxIterations && high - low > 1e-12 * high; ++i) {
    const double middle = 0.5 * (low + high);
    (ChiSquareUpperTail(middle, dof) > upper_tail ? low : high) = middle;
  }
  return 0.5 * (low + high);
}

}  // namespace beamid::solver
