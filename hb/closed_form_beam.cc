#include "hb/closed_form_beam.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

namespace beamid::hb {
namespace {

constexpr double kPi = std::numbers::pi;
// Below this μL the sin/sinh differences are summed as power series (no
// cancellation); above it the hyperbolic terms become decaying exponentials.
constexpr double kSeriesLimit = 1.0;

// Root of f on [a, b] (f(a), f(b) of opposite signs) by bisection to the
// last representable digit: slow but cannot fail on a valid bracket.
template <typename F>
double Bisect(F f, double a, double b) {
  double fa = f(a);
  const double fb = f(b);
  if (fa == 0.0) return a;
  if (fb == 0.0) return b;
  if ((fa > 0.0) == (fb > 0.0)) throw std::logic_error("closed_form_beam: root bracket without a sign change");
  for (int i = 0; i < 200; ++i) {
    const double m = 0.5 * (a + b);
    if (m == a || m == b) break;
    const double fm = f(m);
    if (fm == 0.0) return m;
    if ((fm > 0.0) == (fa > 0.0)) {
      a = m;
      fa = fm;
    } else {
      b = m;
    }
  }
  return 0.5 * (a + b);
}

// The Krylov-type functions f_k, k = 0…3: f0 = sin z − sinh z and
// f_{k+1} = f_k' (so f1 = cos − cosh, f2 = −sin − sinh, f3 = −cos − cosh,
// f4 = f0). Each is −2·Σ_j z^{4j+3−k}/(4j+3−k)!, a series of one sign, summed
// for small z where the closed form would cancel.
double Krylov(int k, double z) {
  k %= 4;
  if (std::abs(z) > kSeriesLimit) {
    switch (k) {
      case 0: return std::sin(z) - std::sinh(z);
      case 1: return std::cos(z) - std::cosh(z);
      case 2: return -std::sin(z) - std::sinh(z);
      default: return -std::cos(z) - std::cosh(z);
    }
  }
  const int first_power = 3 - k;
  double term = 1.0;
  for (int p = 1; p <= first_power; ++p) term *= z / p;
  double sum = term;
  for (int power = first_power; power < 80; power += 4) {
    for (int p = power + 1; p <= power + 4; ++p) term *= z / p;
    sum += term;
    if (std::abs(term) <= 1e-17 * std::abs(sum)) break;
  }
  return -2.0 * sum;
}

// k-th derivative of sin and cos at z (unit wavenumber).
double SinDerivative(double z, int k) {
  switch (k % 4) {
    case 0: return std::sin(z);
    case 1: return std::cos(z);
    case 2: return -std::sin(z);
    default: return -std::cos(z);
  }
}
double CosDerivative(double z, int k) { return SinDerivative(z, k + 1); }

// Gauss–Legendre nodes and weights on [−1, 1], by Newton on Pₙ.
struct GaussRule {
  static constexpr int kOrder = 10;
  std::array<double, kOrder> nodes{};
  std::array<double, kOrder> weights{};
  GaussRule() {
    for (int i = 0; i < kOrder; ++i) {
      double x = std::cos(kPi * (i + 0.75) / (kOrder + 0.5));
      double derivative = 1.0;
      for (int iteration = 0; iteration < 100; ++iteration) {
        double p0 = 1.0, p1 = x;
        for (int n = 2; n <= kOrder; ++n) {
          const double p2 = ((2.0 * n - 1.0) * x * p1 - (n - 1.0) * p0) / n;
          p0 = p1;
          p1 = p2;
        }
        derivative = kOrder * (x * p1 - p0) / (x * x - 1.0);
        const double step = p1 / derivative;
        x -= step;
        if (std::abs(step) < 1e-16) break;
      }
      nodes[i] = x;
      weights[i] = 2.0 / ((1.0 - x * x) * derivative * derivative);
    }
  }
};

}  // namespace

double CharacteristicFunction(double lambda_l, double stiffness_l) {
  const double b = lambda_l;
  const double inverse_cosh = 1.0 / std::cosh(b);
  const double clamped = inverse_cosh - std::cos(b);
  if (std::isinf(stiffness_l)) return clamped;
  return stiffness_l * clamped + b * (std::sin(b) - std::cos(b) * std::tanh(b));
}

std::vector<double> CharacteristicRoots(double stiffness_l, int count) {
  if (!(stiffness_l >= 0.0))
    throw std::invalid_argument("closed-form beam: the support stiffness k1·L must be >= 0, got " +
                                std::to_string(stiffness_l));
  if (count < 1) throw std::invalid_argument("closed-form beam: ask for at least one root");
  std::vector<double> roots;
  for (int n = 1; n <= count; ++n) {
    // Pinned (k1 = 0) root: tan β = tanh β in (nπ, nπ + π/2).
    const double pinned = Bisect([](double b) { return std::sin(b) - std::cos(b) * std::tanh(b); }, n * kPi,
                                 n * kPi + 0.5 * kPi);
    // Clamped (k1 = ∞) root: cos β·cosh β = 1 next to (n + ½)π, on the side where cos > 0.
    const double centre = (n + 0.5) * kPi;
    const double clamped = Bisect([](double b) { return 1.0 / std::cosh(b) - std::cos(b); }, centre,
                                  centre + (n % 2 == 1 ? 0.3 : -0.3));
    if (stiffness_l == 0.0) {
      roots.push_back(pinned);
    } else if (std::isinf(stiffness_l)) {
      roots.push_back(clamped);
    } else {
      roots.push_back(Bisect([&](double b) { return CharacteristicFunction(b, stiffness_l); }, pinned, clamped));
    }
  }
  return roots;
}

std::array<double, 2> ClosedFormShape::Basis2(double x, int k) const {
  const double mu = wavenumber_per_m_;
  switch (basis_) {
    case Basis::kStatic: {
      // (x/L)³ and (x/L)².
      const double s = x / length_m_;
      const double inverse_l = 1.0 / length_m_;
      const std::array<double, 5> cubic = {s * s * s, 3.0 * s * s * inverse_l, 6.0 * s * inverse_l * inverse_l,
                                           6.0 * inverse_l * inverse_l * inverse_l, 0.0};
      const std::array<double, 5> square = {s * s, 2.0 * s * inverse_l, 2.0 * inverse_l * inverse_l, 0.0, 0.0};
      return {cubic[k], square[k]};
    }
    case Basis::kSeries: {
      const double factor = std::pow(mu, k);
      return {factor * Krylov(k, mu * x), factor * Krylov(k + 1, mu * x)};
    }
    case Basis::kExponential: {
      // φa = −e^{−μL}(sin μx + cos μx) + e^{μ(x−L)},  φb = sin μx − cos μx + e^{−μx}:
      // both satisfy φ(0) = φ'(0) = 0 and stay O(1) for any μL.
      const double factor = std::pow(mu, k);
      const double z = mu * x;
      const double decay_l = std::exp(-mu * length_m_);
      const double sin_k = SinDerivative(z, k), cos_k = CosDerivative(z, k);
      return {factor * (-decay_l * (sin_k + cos_k) + std::exp(mu * (x - length_m_))),
              factor * (sin_k - cos_k + (k % 2 == 0 ? 1.0 : -1.0) * std::exp(-z))};
    }
  }
  return {0.0, 0.0};
}

double ClosedFormShape::JumpTerm(double z, int k) const {
  if (jump_weight_ == 0.0 || z <= 0.0) return 0.0;
  const double mu = wavenumber_per_m_;
  if (basis_ == Basis::kStatic) {
    const std::array<double, 5> g = {z * z * z / 6.0, z * z / 2.0, z, 1.0, 0.0};
    return jump_weight_ * g[k];
  }
  // g = (sinh μz − sin μz)/(2μ³) = −f0(μz)/(2μ³).
  return -jump_weight_ * std::pow(mu, k - 3) * Krylov(k, mu * z) / 2.0;
}

double ClosedFormShape::Value(double position_m, int derivative) const {
  if (derivative < 0 || derivative > 4) throw std::invalid_argument("closed-form shape: derivative must be 0…4");
  const std::array<double, 2> basis = Basis2(position_m, derivative);
  return coefficients_[0] * basis[0] + coefficients_[1] * basis[1] +
         JumpTerm(position_m - jump_position_m_, derivative);
}

double ClosedFormShape::SquareIntegral(int derivative) const {
  static const GaussRule rule;
  std::vector<double> breaks;
  const int panels = 8 + 2 * static_cast<int>(std::ceil(wavenumber_per_m_ * length_m_));
  for (int p = 0; p <= panels; ++p) breaks.push_back(length_m_ * p / panels);
  if (jump_weight_ != 0.0 && jump_position_m_ > 0.0 && jump_position_m_ < length_m_) {
    breaks.push_back(jump_position_m_);
    std::sort(breaks.begin(), breaks.end());
  }
  double sum = 0.0;
  for (std::size_t p = 0; p + 1 < breaks.size(); ++p) {
    const double half = 0.5 * (breaks[p + 1] - breaks[p]);
    const double mid = 0.5 * (breaks[p + 1] + breaks[p]);
    for (int i = 0; i < GaussRule::kOrder; ++i) {
      const double value = Value(mid + half * rule.nodes[i], derivative);
      sum += half * rule.weights[i] * value * value;
    }
  }
  return sum;
}

ClosedFormBeam::ClosedFormBeam(const BeamProperties& beam, double support_stiffness_Nm_rad)
    : beam_(beam), support_stiffness_Nm_rad_(support_stiffness_Nm_rad) {
  beam_.Validate();
  if (!(support_stiffness_Nm_rad >= 0.0) || std::isinf(support_stiffness_Nm_rad))
    throw std::invalid_argument("closed-form beam: the support stiffness k1 must be a finite number >= 0 N*m/rad");
}

double ClosedFormBeam::StiffnessPerBendingStiffness_per_m() const {
  return support_stiffness_Nm_rad_ / beam_.BendingStiffness_Nm2();
}

double ClosedFormBeam::Wavenumber_per_m(double omega_rad_s) const {
  return std::pow(beam_.MassPerLength_kg_m() * omega_rad_s * omega_rad_s / beam_.BendingStiffness_Nm2(), 0.25);
}

std::vector<double> ClosedFormBeam::NaturalFrequencies_rad_s(int count) const {
  const double length = beam_.length_m;
  const std::vector<double> roots = CharacteristicRoots(StiffnessPerBendingStiffness_per_m() * length, count);
  std::vector<double> omegas;
  for (double root : roots)
    omegas.push_back(root * root / (length * length) *
                     std::sqrt(beam_.BendingStiffness_Nm2() / beam_.MassPerLength_kg_m()));
  return omegas;
}

ClosedFormShape::Basis ClosedFormShape::ChooseBasis(double mu, double length) {
  if (mu == 0.0) return Basis::kStatic;
  return mu * length <= kSeriesLimit ? Basis::kSeries : Basis::kExponential;
}

ClosedFormShape ClosedFormBeam::Solve(double omega_rad_s, double moment_rhs, double force_position_m,
                                      double force_weight) const {
  if (!std::isfinite(omega_rad_s) || omega_rad_s < 0.0)
    throw std::invalid_argument("closed-form beam: the angular frequency must be a finite number >= 0 rad/s");
  ClosedFormShape shape;
  shape.length_m_ = beam_.length_m;
  shape.wavenumber_per_m_ = Wavenumber_per_m(omega_rad_s);
  shape.basis_ = ClosedFormShape::ChooseBasis(shape.wavenumber_per_m_, shape.length_m_);
  shape.jump_position_m_ = force_position_m;
  shape.jump_weight_ = force_weight;
  const double length = beam_.length_m;
  const double k1 = StiffnessPerBendingStiffness_per_m();
  std::array<std::array<double, 2>, 3> phi;
  for (int k = 0; k < 3; ++k) phi[k] = shape.Basis2(length, k);
  auto jump = [&](int k) { return shape.JumpTerm(length - force_position_m, k); };
  // y(L) = 0 and y''(L) + k1·y'(L) = moment_rhs, the jump term moved right.
  const double a11 = phi[0][0], a12 = phi[0][1];
  const double a21 = phi[2][0] + k1 * phi[1][0], a22 = phi[2][1] + k1 * phi[1][1];
  const double r1 = -jump(0), r2 = moment_rhs - (jump(2) + k1 * jump(1));
  const double det = a11 * a22 - a12 * a21;
  shape.coefficients_[0] = (r1 * a22 - a12 * r2) / det;
  shape.coefficients_[1] = (a11 * r2 - a21 * r1) / det;
  return shape;
}

ClosedFormShape ClosedFormBeam::EndMomentShape(double omega_rad_s) const {
  return Solve(omega_rad_s, 1.0, 0.0, 0.0);
}

ClosedFormShape ClosedFormBeam::PointForceShape(double omega_rad_s, double force_position_m) const {
  if (!(force_position_m >= 0.0 && force_position_m <= beam_.length_m))
    throw std::invalid_argument("closed-form beam: the force position " + std::to_string(force_position_m) +
                                " m lies outside the beam [0, " + std::to_string(beam_.length_m) + "] m");
  return Solve(omega_rad_s, 0.0, force_position_m, 1.0);
}

double ClosedFormBeam::RotationPerEndMoment_rad_Nm(double omega_rad_s) const {
  return EndMomentShape(omega_rad_s).Value(beam_.length_m, 1) / beam_.BendingStiffness_Nm2();
}

ClosedFormShape ClosedFormBeam::ModeShape(int index) const {
  if (index < 0) throw std::invalid_argument("closed-form beam: mode index must be >= 0");
  const double length = beam_.length_m;
  const double root = CharacteristicRoots(StiffnessPerBendingStiffness_per_m() * length, index + 1).back();
  ClosedFormShape shape;
  shape.length_m_ = length;
  shape.wavenumber_per_m_ = root / length;
  shape.basis_ = ClosedFormShape::ChooseBasis(shape.wavenumber_per_m_, length);
  const double k1 = StiffnessPerBendingStiffness_per_m();
  std::array<std::array<double, 2>, 3> phi;
  for (int k = 0; k < 3; ++k) phi[k] = shape.Basis2(length, k);
  // At a root the two boundary rows are parallel: take the null vector of the
  // larger one (the moment row scaled by 1/μ² to compare like with like).
  const double mu2 = shape.wavenumber_per_m_ * shape.wavenumber_per_m_;
  const double row_y[2] = {phi[0][0], phi[0][1]};
  const double row_m[2] = {(phi[2][0] + k1 * phi[1][0]) / mu2, (phi[2][1] + k1 * phi[1][1]) / mu2};
  const double* row = std::hypot(row_y[0], row_y[1]) >= std::hypot(row_m[0], row_m[1]) ? row_y : row_m;
  shape.coefficients_[0] = row[1];
  shape.coefficients_[1] = -row[0];
  // Scale to max|w| = 1: a grid search, then Newton on w' = 0.
  const int samples = 200 * (index + 2);
  double best_x = 0.0, best_abs = -1.0;
  for (int i = 0; i <= samples; ++i) {
    const double x = length * i / samples;
    const double value = std::abs(shape.Value(x));
    if (value > best_abs) {
      best_abs = value;
      best_x = x;
    }
  }
  for (int iteration = 0; iteration < 20 && best_x > 0.0 && best_x < length; ++iteration) {
    const double step = shape.Value(best_x, 1) / shape.Value(best_x, 2);
    const double next = std::clamp(best_x - step, best_x - length / samples, best_x + length / samples);
    if (next == best_x) break;
    best_x = next;
  }
  const double peak = shape.Value(best_x);
  shape.coefficients_[0] /= peak;
  shape.coefficients_[1] /= peak;
  return shape;
}

}  // namespace beamid::hb
