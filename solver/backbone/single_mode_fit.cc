#include "solver/backbone/single_mode_fit.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <stdexcept>

#include <Eigen/Cholesky>
#include <Eigen/QR>
#include <fmt/core.h>

#include "hb/option_checks.h"

namespace beamid::solver {
namespace {

// Central-difference gradient of a scalar function of the parameters.
Eigen::VectorXd Gradient(const std::function<double(const Eigen::VectorXd&)>& f, const Eigen::VectorXd& x) {
  Eigen::VectorXd g(x.size());
  for (int j = 0; j < x.size(); ++j) {
    const double h = 1e-6 * std::max(std::abs(x[j]), 1e-6 * x.cwiseAbs().maxCoeff() + 1e-300);
    Eigen::VectorXd plus = x, minus = x;
    plus[j] += h;
    minus[j] -= h;
    g[j] = (f(plus) - f(minus)) / (2 * h);
  }
  return g;
}

// AICc with the noise scale left free (see the header).
double Aicc(double chi_square, int n, int k) {
  return n * std::log(std::max(chi_square, 1e-300) / n) + 2.0 * k + 2.0 * k * (k + 1) / std::max(1, n - k - 1);
}

double Std(const Eigen::VectorXd& gradient, const Eigen::MatrixXd& covariance) {
  return std::sqrt(std::max(0.0, gradient.dot(covariance * gradient)));
}

// 1, s, …, s^degree; or 1, s^exponent when exponent > 0.
Eigen::VectorXd Terms(double s, int degree, double exponent) {
  if (exponent > 0) return Eigen::Vector2d(1.0, std::pow(s, exponent));
  Eigen::VectorXd b(degree + 1);
  b[0] = 1.0;
  for (int j = 1; j <= degree; ++j) b[j] = b[j - 1] * s;
  return b;
}

}  // namespace

double SingleModeFit::ReducedChiSquare() const {
  const int dof = num_residuals - NumParameters();
  return dof > 0 ? chi_square / dof : std::numeric_limits<double>::quiet_NaN();
}

Eigen::VectorXd SingleModeFit::FrequencyBasis(double a) const {
  return Terms(a / reference_amplitude_m, frequency_degree, frequency_exponent);
}

Eigen::VectorXd SingleModeFit::DampingBasis(double a) const {
  return Terms(a / reference_amplitude_m, damping_degree, damping_exponent);
}

namespace {
// A(a), ω_n and ζ from a parameter vector at amplitude `a`.
struct ModalValues {
  std::complex<double> modal_constant;
  double omega_n, zeta;
};
ModalValues Evaluate(const SingleModeFit& fit, const Eigen::VectorXd& x, double a) {
  const int na = fit.NumModalConstantTerms();
  const auto bp = fit.FrequencyBasis(a), bq = fit.DampingBasis(a);
  const double s = a / fit.reference_amplitude_m;
  std::complex<double> modal_constant(x[0], x[1]);
  if (na == 3) modal_constant += x[2] * s * s;
  const double omega_n_sq = x.segment(na, bp.size()).dot(bp);
  const double omega_n = std::sqrt(std::max(omega_n_sq, 0.0));
  const double zeta_omega = x.segment(na + bp.size(), bq.size()).dot(bq);
  return {modal_constant, omega_n, omega_n > 0 ? zeta_omega / omega_n : std::numeric_limits<double>::quiet_NaN()};
}

}  // namespace

std::complex<double> SingleModeFit::ModalConstantAt(double a) const { return Evaluate(*this, parameters, a).modal_constant; }

Eigen::Matrix2d SingleModeFit::ModalConstantCovariance(double a) const {
  Eigen::MatrixXd gradients(2, parameters.size());
  gradients.row(0) = Gradient([&](const Eigen::VectorXd& x) { return Evaluate(*this, x, a).modal_constant.real(); }, parameters);
  gradients.row(1) = Gradient([&](const Eigen::VectorXd& x) { return Evaluate(*this, x, a).modal_constant.imag(); }, parameters);
  return gradients * covariance * gradients.transpose();
}

Eigen::Vector2d SingleModeFit::ModalConstantResidualCovariance(double a) const {
  if (residual_covariance.size() != parameters.size()) return Eigen::Vector2d::Zero();
  return {Gradient([&](const Eigen::VectorXd& x) { return Evaluate(*this, x, a).modal_constant.real(); }, parameters)
              .dot(residual_covariance),
          Gradient([&](const Eigen::VectorXd& x) { return Evaluate(*this, x, a).modal_constant.imag(); }, parameters)
              .dot(residual_covariance)};
}

double SingleModeFit::NaturalFrequency_rad_s(double a) const { return Evaluate(*this, parameters, a).omega_n; }

double SingleModeFit::DampingRatio(double a) const { return Evaluate(*this, parameters, a).zeta; }

Eigen::VectorXd SingleModeFit::NaturalFrequencyGradient(double a) const {
  return Gradient([&](const Eigen::VectorXd& x) { return Evaluate(*this, x, a).omega_n; }, parameters);
}

Eigen::VectorXd SingleModeFit::DampingGradient(double a) const {
  return Gradient([&](const Eigen::VectorXd& x) { return Evaluate(*this, x, a).zeta; }, parameters);
}

double SingleModeFit::NaturalFrequencyStd_rad_s(double a) const {
  return Std(NaturalFrequencyGradient(a), covariance);
}

double SingleModeFit::DampingRatioStd(double a) const { return Std(DampingGradient(a), covariance); }

namespace {
// dζ/da by a central difference in amplitude.
double Slope(const SingleModeFit& fit, const Eigen::VectorXd& x, double a) {
  const double h = 1e-4 * fit.reference_amplitude_m;
  return (Evaluate(fit, x, a + h).zeta - Evaluate(fit, x, a - h).zeta) / (2 * h);
}

std::string FormOf(int degree, double exponent) {
  return exponent > 0 ? fmt::format("power {:g}", exponent) : fmt::format("polynomial {}", degree);
}
}  // namespace

double SingleModeFit::DampingSlope_per_m(double a) const { return Slope(*this, parameters, a); }

double SingleModeFit::DampingSlopeStd_per_m(double a) const {
  return Std(Gradient([&](const Eigen::VectorXd& x) { return Slope(*this, x, a); }, parameters), covariance);
}

std::string SingleModeFit::FormName() const {
  return "wn^2: " + FormOf(frequency_degree, frequency_exponent) + ", zeta*wn: " + FormOf(damping_degree, damping_exponent) +
         (amplitude_dependent_modal_constant ? ", A(a) = A0 + A2*s^2" : ", A constant");
}

SingleModeFitOptions SingleModeFit::Form() const {
  return {.frequency_degree = frequency_degree,
          .damping_degree = damping_degree,
          .frequency_exponent = frequency_exponent,
          .damping_exponent = damping_exponent,
          .amplitude_dependent_modal_constant = amplitude_dependent_modal_constant,
          .reference_amplitude_m = reference_amplitude_m};
}

std::complex<double> SingleModeFit::DynamicTerm(double a, double omega) const {
  const int na = NumModalConstantTerms();
  const auto bp = FrequencyBasis(a), bq = DampingBasis(a);
  const double omega_n_sq = parameters.segment(na, bp.size()).dot(bp);
  const double zeta_omega = parameters.segment(na + bp.size(), bq.size()).dot(bq);
  return {omega_n_sq - omega * omega, 2 * omega * zeta_omega};
}

namespace {
// Of (Re G, Im G, a).
Eigen::Matrix3d InputCovariance(const SingleModePoint& p) {
  Eigen::Matrix3d c;
  c.topLeftCorner<2, 2>() = p.inverse_receptance_covariance;
  c.block<2, 1>(0, 2) = p.amplitude_inverse_receptance_covariance;
  c.block<1, 2>(2, 0) = p.amplitude_inverse_receptance_covariance.transpose();
  c(2, 2) = p.amplitude_variance_m2;
  return c;
}
}  // namespace

std::vector<SingleModePoint> WithoutResidual(const std::vector<SingleModePoint>& points, double residual) {
  std::vector<SingleModePoint> out = points;
  if (residual == 0.0) return out;
  for (auto& p : out) {
    // X_d/F − R: the mode's own part; G' = 1/(1/G − R), dG'/dG = (G'/G)².
    const std::complex<double> g = p.inverse_receptance_N_m;
    const std::complex<double> modal = 1.0 / (1.0 / g - residual);
    // The mode's amplitude a' = a·|w|, w = G/G' = 1 − R·G, moves with G too.
    const std::complex<double> d = (modal / g) * (modal / g), w = 1.0 - residual * g;
    Eigen::Matrix3d jacobian = Eigen::Matrix3d::Zero();
    jacobian.topLeftCorner<2, 2>() << d.real(), -d.imag(), d.imag(), d.real();
    jacobian.bottomRows<1>() << -p.amplitude_m * residual * w.real() / std::abs(w),
        -p.amplitude_m * residual * w.imag() / std::abs(w), std::abs(w);
    const Eigen::Matrix3d covariance = jacobian * InputCovariance(p) * jacobian.transpose();
    p.inverse_receptance_N_m = modal;
    p.inverse_receptance_covariance = covariance.topLeftCorner<2, 2>();
    p.amplitude_inverse_receptance_covariance = covariance.block<2, 1>(0, 2);
    p.amplitude_variance_m2 = covariance(2, 2);
    p.amplitude_m *= std::abs(w);
  }
  return out;
}

void SingleModeFitOptions::Validate() const {
  using namespace option_checks;
  RequireAtLeast("SingleModeFitOptions.frequency_degree", frequency_degree, 0);
  RequireAtLeast("SingleModeFitOptions.damping_degree", damping_degree, 0);
  RequireNonNegative("SingleModeFitOptions.frequency_exponent (0: polynomial)", frequency_exponent);
  RequireNonNegative("SingleModeFitOptions.damping_exponent (0: polynomial)", damping_exponent);
  if (!std::isfinite(residual_receptance_m_N))
    Refuse("SingleModeFitOptions.residual_receptance_m_N", FormatValue(residual_receptance_m_N), "finite");
  RequirePositive("SingleModeFitOptions.reference_amplitude_m", reference_amplitude_m);
  RequirePositive("SingleModeFitOptions.default_relative_std", default_relative_std);
  RequireAtLeast("SingleModeFitOptions.reweighting_iterations", reweighting_iterations, 0);
}

SingleModeFit FitSingleMode(const std::vector<SingleModePoint>& measured_points, const SingleModeFitOptions& options) {
  options.Validate();
  const std::vector<SingleModePoint> points = WithoutResidual(measured_points, options.residual_receptance_m_N);
  SingleModeFit fit;
  fit.residual_receptance_m_N = options.residual_receptance_m_N;
  fit.num_searched_parameters = options.residual_receptance_m_N != 0.0 ? 1 : 0;
  fit.frequency_degree = options.frequency_exponent > 0 ? 1 : options.frequency_degree;
  fit.damping_degree = options.damping_exponent > 0 ? 1 : options.damping_degree;
  fit.frequency_exponent = options.frequency_exponent;
  fit.damping_exponent = options.damping_exponent;
  fit.amplitude_dependent_modal_constant = options.amplitude_dependent_modal_constant;
  fit.reference_amplitude_m = options.reference_amplitude_m;
  const int na = fit.NumModalConstantTerms();
  const int np = static_cast<int>(fit.FrequencyBasis(1.0).size()), nq = static_cast<int>(fit.DampingBasis(1.0).size());
  const int k = na + np + nq;
  const int n = 2 * static_cast<int>(points.size());
  fit.num_residuals = n;
  fit.parameters = Eigen::VectorXd::Zero(k);
  fit.covariance = Eigen::MatrixXd::Zero(k, k);
  if (n < k + 2) return fit;

  // A·G = D with A = A_r + i·A_i (+ A_2·s²), per point:
  //   real: [Re G, −Im G, s²·Re G, −b_p, 0] x = −ω²;  imaginary: [Im G, Re G, s²·Im G, 0, −2ω b_q] x = 0.
  Eigen::MatrixXd design = Eigen::MatrixXd::Zero(n, k);
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(n);
  std::vector<Eigen::Matrix2d> g_cov(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    const auto& p = points[i];
    const std::complex<double> g = p.inverse_receptance_N_m;
    const double s = p.amplitude_m / fit.reference_amplitude_m;
    design.block(2 * i, 0, 2, 2) << g.real(), -g.imag(), g.imag(), g.real();
    if (na == 3) design.block(2 * i, 2, 2, 1) << s * s * g.real(), s * s * g.imag();
    design.block(2 * i, na, 1, np) = -fit.FrequencyBasis(p.amplitude_m).transpose();
    rhs[2 * i] = -p.omega_rad_s * p.omega_rad_s;
    design.block(2 * i + 1, na + np, 1, nq) = -2 * p.omega_rad_s * fit.DampingBasis(p.amplitude_m).transpose();
    g_cov[i] = p.inverse_receptance_covariance;
    if (g_cov[i].trace() <= 0)
      g_cov[i] = Eigen::Matrix2d::Identity() * std::pow(options.default_relative_std * std::abs(g), 2);
  }
  // Column scaling for conditioning; A starts from the unweighted solution.
  const Eigen::VectorXd scale = design.colwise().norm().cwiseMax(1e-300).cwiseInverse();
  auto solve = [&](const Eigen::MatrixXd& a, const Eigen::VectorXd& b) -> Eigen::VectorXd {
    return scale.asDiagonal() * Eigen::ColPivHouseholderQR<Eigen::MatrixXd>(a * scale.asDiagonal()).solve(b);
  };
  Eigen::VectorXd x = solve(design, rhs);
  Eigen::MatrixXd whitened_design = design;
  Eigen::VectorXd whitened_rhs = rhs;
  std::vector<Eigen::Matrix2d> whitening(points.size());
  for (int iteration = 0; iteration <= options.reweighting_iterations; ++iteration) {
    fit.parameters = x;
    for (std::size_t i = 0; i < points.size(); ++i) {
      // Cov(A·G) = |A|²·Cov(G) for the rotation by A (to first order, the noise being isotropic-ish).
      const std::complex<double> modal_constant = fit.ModalConstantAt(points[i].amplitude_m);
      Eigen::Matrix2d rotation;
      rotation << modal_constant.real(), -modal_constant.imag(), modal_constant.imag(), modal_constant.real();
      Eigen::Matrix2d cov = rotation * g_cov[i] * rotation.transpose();
      cov(0, 0) += std::pow(2 * points[i].omega_rad_s * points[i].omega_std_rad_s, 2);
      // Inverse of the Cholesky factor L of the pair's covariance, by hand for 2×2.
      const double l11 = std::sqrt(cov(0, 0)), l21 = cov(1, 0) / l11;
      const double l22 = std::sqrt(std::max(cov(1, 1) - l21 * l21, 1e-30 * cov(1, 1)));
      Eigen::Matrix2d l_inverse;
      l_inverse << 1 / l11, 0, -l21 / (l11 * l22), 1 / l22;
      whitening[i] = l_inverse;
      whitened_design.middleRows(2 * i, 2) = l_inverse * design.middleRows(2 * i, 2);
      const double r0 = rhs[2 * i], r1 = rhs[2 * i + 1];
      whitened_rhs[2 * i] = l_inverse(0, 0) * r0;
      whitened_rhs[2 * i + 1] = l_inverse(1, 0) * r0 + l_inverse(1, 1) * r1;
    }
    x = solve(whitened_design, whitened_rhs);
  }
  fit.parameters = x;
  fit.chi_square = (whitened_design * x - whitened_rhs).squaredNorm();
  const Eigen::MatrixXd scaled = whitened_design * scale.asDiagonal();
  const Eigen::MatrixXd normal_inverse = (scaled.transpose() * scaled).ldlt().solve(Eigen::MatrixXd::Identity(k, k));
  const Eigen::VectorXd unweighted = design * x - rhs;
  fit.noise_chi_square = fit.chi_square;
  if (std::any_of(points.begin(), points.end(), [](const SingleModePoint& p) { return p.amplitude_variance_m2 > 0; })) {
    // The estimator's covariance under every input's noise, G's weights kept:
    // (Jᵀ J)⁻¹ Jᵀ S J (Jᵀ J)⁻¹ with J the whitened design and S each pair's
    // whitened covariance, the amplitude's share through the model's slope in a.
    Eigen::MatrixXd meat = Eigen::MatrixXd::Zero(k, k);
    fit.noise_chi_square = 0.0;
    for (std::size_t i = 0; i < points.size(); ++i) {
      const SingleModePoint& p = points[i];
      const std::complex<double> g = p.inverse_receptance_N_m, modal_constant = fit.ModalConstantAt(p.amplitude_m);
      const auto pair = [&](double a) {
        const std::complex<double> r = fit.ModalConstantAt(a) * g - fit.DynamicTerm(a, p.omega_rad_s);
        return Eigen::Vector2d(r.real(), r.imag());
      };
      Eigen::Matrix<double, 2, 3> jacobian;
      jacobian.leftCols<2>() << modal_constant.real(), -modal_constant.imag(), modal_constant.imag(),
          modal_constant.real();
      const double h = 1e-4 * p.amplitude_m;
      jacobian.col(2) = Eigen::Vector2d::Zero();
      if (p.amplitude_variance_m2 > 0) jacobian.col(2) = (pair(p.amplitude_m + h) - pair(p.amplitude_m - h)) / (2 * h);
      Eigen::Matrix3d input = InputCovariance(p);
      input.topLeftCorner<2, 2>() = g_cov[i];
      Eigen::Matrix2d full = jacobian * input * jacobian.transpose();
      full(0, 0) += std::pow(2 * p.omega_rad_s * p.omega_std_rad_s, 2);
      const Eigen::Matrix2d whitened = whitening[i] * full * whitening[i].transpose();
      const Eigen::MatrixXd rows = scaled.middleRows(2 * i, 2);
      meat += rows.transpose() * whitened * rows;
      const Eigen::Vector2d r = unweighted.segment<2>(2 * i);
      fit.noise_chi_square += r.dot(full.ldlt().solve(r));
    }
    fit.covariance = scale.asDiagonal() * (normal_inverse * meat * normal_inverse) * scale.asDiagonal();
  } else {
    fit.covariance = scale.asDiagonal() * normal_inverse * scale.asDiagonal();
  }
  const int dof = n - fit.NumParameters();
  fit.covariance *= std::max(1.0, dof > 0 ? fit.noise_chi_square / dof : 1.0);
  fit.aicc = Aicc(fit.chi_square, n, fit.NumParameters());
  double sum_sq = 0.0;
  for (int i = 0; i < n; i += 2) sum_sq += unweighted[i] * unweighted[i];
  fit.backbone_residual_rms_rad2_s2 = std::sqrt(sum_sq / (n / 2));
  // Terms the data cannot tell apart (a level held at one amplitude makes
  // s, s², … copies of 1): no fit.
  Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(scaled);
  qr.setThreshold(1e-10);
  fit.ok = std::isfinite(fit.chi_square) && fit.parameters.allFinite() && qr.rank() == k;
  return fit;
}

std::vector<double> PowerLawExponentGrid() {
  std::vector<double> grid;
  for (int k = 1; k <= 16; ++k) grid.push_back(0.25 * k);  // 0.25 … 4
  return grid;
}

SingleModeFit FitSingleModeChoosingExponents(const std::vector<SingleModePoint>& points,
                                             const SingleModeFitOptions& options) {
  options.Validate();
  const std::vector<double> none = {0.0};
  const std::vector<double> grid = PowerLawExponentGrid();
  SingleModeFit best;
  for (double alpha : options.frequency_exponent > 0 ? grid : none)
    for (double beta : options.damping_exponent > 0 ? grid : none) {
      SingleModeFitOptions o = options;
      o.frequency_exponent = alpha;
      o.damping_exponent = beta;
      SingleModeFit fit = FitSingleMode(points, o);
      if (!fit.ok) continue;
      if (!best.ok || fit.chi_square < best.chi_square) best = std::move(fit);
    }
  if (!best.ok) return best;
  // Count the chosen exponents as parameters: redo the scaling and the AICc.
  best.num_searched_parameters += (options.frequency_exponent > 0) + (options.damping_exponent > 0);
  const int dof = best.num_residuals - best.NumParameters();
  const double reduced = dof > 0 ? best.noise_chi_square / dof : std::numeric_limits<double>::quiet_NaN();
  if (reduced > 1) {
    const int searched_before = best.residual_receptance_m_N != 0.0 ? 1 : 0;
    const int dof_before = best.num_residuals - static_cast<int>(best.parameters.size()) - searched_before;
    best.covariance *= reduced / std::max(1.0, best.noise_chi_square / dof_before);
  }
  best.aicc = Aicc(best.chi_square, best.num_residuals, best.NumParameters());
  best.ok = best.num_residuals > best.NumParameters() + 1;
  return best;
}

}  // namespace beamid::solver

namespace beamid::solver {

namespace {

// R is searched within this fraction of the largest |X_d/F| either way.
constexpr double kResidualRange = 0.02;

// The R minimising `chi_square` within ±2 % of the largest |X_d/F| (χ² need
// not be convex in R: a coarse scan, then golden section in the best cell).
double MinimiseOverResidual(double peak_receptance_m_N, const std::function<double(double)>& chi_square) {
  constexpr int kScan = 40;
  double best = 0.0, best_chi = chi_square(0.0);
  const double step = 2 * kResidualRange * peak_receptance_m_N / kScan;
  for (int k = 0; k <= kScan; ++k) {
    const double r = -kResidualRange * peak_receptance_m_N + k * step;
    const double c = chi_square(r);
    if (c < best_chi) best_chi = c, best = r;
  }
  double lo = best - step, hi = best + step;
  const double ratio = (std::sqrt(5.0) - 1) / 2;
  double x1 = hi - ratio * (hi - lo), x2 = lo + ratio * (hi - lo);
  double c1 = chi_square(x1), c2 = chi_square(x2);
  for (int iteration = 0; iteration < 40; ++iteration) {
    if (c1 < c2) {
      hi = x2, x2 = x1, c2 = c1;
      x1 = hi - ratio * (hi - lo), c1 = chi_square(x1);
    } else {
      lo = x1, x1 = x2, c1 = c2;
      x2 = lo + ratio * (hi - lo), c2 = chi_square(x2);
    }
  }
  const double r = 0.5 * (lo + hi);
  return chi_square(r) > best_chi ? best : r;
}

double PeakReceptance(const std::vector<SingleModePoint>& points) {
  double peak = 0.0;
  for (const auto& p : points) peak = std::max(peak, 1.0 / std::abs(p.inverse_receptance_N_m));
  return peak;
}

// The groups' fits, each with its own form, all with the residual R.
std::vector<SingleModeFit> FitGroups(const std::vector<std::vector<SingleModePoint>>& groups,
                                     const std::vector<SingleModeFitOptions>& forms, double residual) {
  std::vector<SingleModeFit> fits;
  for (std::size_t g = 0; g < groups.size(); ++g) {
    SingleModeFitOptions o = forms[g];
    o.residual_receptance_m_N = residual;
    fits.push_back(FitSingleMode(groups[g], o));
  }
  return fits;
}

}  // namespace

double ResidualReceptanceStd(const std::vector<std::vector<SingleModePoint>>& groups,
                             const std::vector<SingleModeFitOptions>& forms, double residual) {
  if (residual == 0.0) return 0.0;
  if (groups.size() != forms.size()) throw std::invalid_argument("ResidualReceptanceStd: one form per group");
  double peak = 0.0;
  for (const auto& group : groups) peak = std::max(peak, PeakReceptance(group));
  // The groups' summed χ² and degrees of freedom at R (a group too small for its form takes no part).
  const auto profile = [&](double r) {
    double chi_square = 0.0;
    int dof = 0;
    for (const SingleModeFit& fit : FitGroups(groups, forms, r)) {
      if (!fit.ok) continue;
      chi_square += fit.chi_square;
      dof += fit.num_residuals - fit.NumParameters();
    }
    return std::pair{chi_square, dof};
  };
  const auto [chi_square, dof] = profile(residual);
  // Not convex at R: R is known only to lie in the range searched (±2 % of the peak), uniformly.
  const double unknown = kResidualRange * peak / std::sqrt(3.0);
  // A step first on the scale of the search, then on R's own σ.
  double std = unknown;
  for (double h : {1e-3 * peak, 0.0}) {
    if (h == 0.0) h = std::clamp(0.5 * std, 1e-6 * peak, 1e-2 * peak);
    const double curvature = (profile(residual + h).first - 2 * chi_square + profile(residual - h).first) / (h * h);
    if (!(curvature > 0)) return unknown;
    std = std::sqrt(2.0 / curvature);
  }
  return std::min(unknown, std * std::sqrt(std::max(1.0, dof > 0 ? chi_square / dof : 1.0)));
}

void IncludeResidualUncertainty(SingleModeFit& fit, const std::vector<SingleModePoint>& points, double residual_std) {
  if (!fit.ok || !(residual_std > 0)) return;
  const SingleModeFitOptions form = fit.Form();
  const double h = 0.1 * residual_std;
  const auto at = [&](double r) {
    SingleModeFitOptions o = form;
    o.residual_receptance_m_N = r;
    return FitSingleMode(points, o);
  };
  const SingleModeFit plus = at(fit.residual_receptance_m_N + h), minus = at(fit.residual_receptance_m_N - h);
  if (!plus.ok || !minus.ok) return;
  const Eigen::VectorXd sensitivity = (plus.parameters - minus.parameters) / (2 * h);
  fit.residual_receptance_std_m_N = residual_std;
  fit.residual_covariance = sensitivity * residual_std * residual_std;
  fit.covariance += sensitivity * sensitivity.transpose() * (residual_std * residual_std);
}

double FitResidualReceptance(const std::vector<SingleModePoint>& points, const SingleModeFitOptions& options) {
  return FitResidualReceptance(std::vector<std::vector<SingleModePoint>>{points}, {options});
}

double FitResidualReceptance(const std::vector<std::vector<SingleModePoint>>& groups,
                             const std::vector<SingleModeFitOptions>& forms) {
  if (groups.size() != forms.size()) throw std::invalid_argument("FitResidualReceptance: one form per group");
  for (const auto& form : forms) form.Validate();
  // A group too small for its form at R = 0 takes no part.
  std::vector<std::vector<SingleModePoint>> fitted;
  std::vector<SingleModeFitOptions> fitted_forms;
  const std::vector<SingleModeFit> at_zero = FitGroups(groups, forms, 0.0);
  for (std::size_t g = 0; g < groups.size(); ++g)
    if (at_zero[g].ok) fitted.push_back(groups[g]), fitted_forms.push_back(forms[g]);
  if (fitted.empty()) return 0.0;
  double peak = 0.0;
  for (const auto& group : fitted) peak = std::max(peak, PeakReceptance(group));
  const auto sum = [&](double residual, auto member) {
    double total = 0.0;
    for (const SingleModeFit& fit : FitGroups(fitted, fitted_forms, residual)) {
      if (!fit.ok) return std::numeric_limits<double>::infinity();
      total += member(fit);
    }
    return total;
  };
  const auto chi_square = [&](const SingleModeFit& fit) { return fit.chi_square; };
  const double r = MinimiseOverResidual(peak, [&](double residual) { return sum(residual, chi_square); });
  // Only when the data ask for it: R must lower the AICc, as one parameter
  // more; each group's AICc counts it, so over several groups the total χ²
  // must fall by the 2 the AIC charges for one parameter.
  if (fitted.size() == 1) {
    const auto aicc = [&](const SingleModeFit& fit) { return fit.aicc; };
    return sum(r, aicc) < sum(0.0, aicc) ? r : 0.0;
  }
  return sum(r, chi_square) + 2 < sum(0.0, chi_square) ? r : 0.0;
}

}  // namespace beamid::solver
