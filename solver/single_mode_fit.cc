#include "solver/single_mode_fit.h"

#include <cmath>
#include <functional>
#include <limits>

#include <Eigen/Cholesky>
#include <Eigen/QR>

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

double Std(const Eigen::VectorXd& gradient, const Eigen::MatrixXd& covariance) {
  return std::sqrt(std::max(0.0, gradient.dot(covariance * gradient)));
}

}  // namespace

double SingleModeFit::ReducedChiSquare() const {
  const int dof = num_residuals - NumParameters();
  return dof > 0 ? chi_square / dof : std::numeric_limits<double>::quiet_NaN();
}

Eigen::VectorXd SingleModeFit::Basis(double amplitude_m, int degree) const {
  Eigen::VectorXd b(degree + 1);
  const double s = amplitude_m / reference_amplitude_m;
  b[0] = 1.0;
  for (int j = 1; j <= degree; ++j) b[j] = b[j - 1] * s;
  return b;
}

namespace {
// ω_n and ζ from a parameter vector (A, p, q) at scaled amplitude basis b.
struct ModalValues {
  double omega_n, zeta;
};
ModalValues Evaluate(const Eigen::VectorXd& x, const Eigen::VectorXd& bp, const Eigen::VectorXd& bq) {
  const double omega_n_sq = x.segment(1, bp.size()).dot(bp);
  const double omega_n = std::sqrt(std::max(omega_n_sq, 0.0));
  const double zeta_omega = x.segment(1 + bp.size(), bq.size()).dot(bq);
  return {omega_n, omega_n > 0 ? zeta_omega / omega_n : std::numeric_limits<double>::quiet_NaN()};
}
}  // namespace

double SingleModeFit::NaturalFrequency_rad_s(double a) const {
  return Evaluate(parameters, Basis(a, frequency_degree), Basis(a, damping_degree)).omega_n;
}

double SingleModeFit::DampingRatio(double a) const {
  return Evaluate(parameters, Basis(a, frequency_degree), Basis(a, damping_degree)).zeta;
}

Eigen::VectorXd SingleModeFit::NaturalFrequencyGradient(double a) const {
  const auto bp = Basis(a, frequency_degree), bq = Basis(a, damping_degree);
  return Gradient([&](const Eigen::VectorXd& x) { return Evaluate(x, bp, bq).omega_n; }, parameters);
}

Eigen::VectorXd SingleModeFit::DampingGradient(double a) const {
  const auto bp = Basis(a, frequency_degree), bq = Basis(a, damping_degree);
  return Gradient([&](const Eigen::VectorXd& x) { return Evaluate(x, bp, bq).zeta; }, parameters);
}

double SingleModeFit::NaturalFrequencyStd_rad_s(double a) const {
  return Std(NaturalFrequencyGradient(a), covariance);
}

double SingleModeFit::DampingRatioStd(double a) const { return Std(DampingGradient(a), covariance); }

namespace {
// dζ/da by a central difference in amplitude (the basis is a polynomial).
double Slope(const SingleModeFit& fit, const Eigen::VectorXd& x, double a) {
  SingleModeFit copy = fit;
  copy.parameters = x;
  const double h = 1e-4 * fit.reference_amplitude_m;
  return (copy.DampingRatio(a + h) - copy.DampingRatio(a - h)) / (2 * h);
}
}  // namespace

double SingleModeFit::DampingSlope_per_m(double a) const { return Slope(*this, parameters, a); }

double SingleModeFit::DampingSlopeStd_per_m(double a) const {
  return Std(Gradient([&](const Eigen::VectorXd& x) { return Slope(*this, x, a); }, parameters), covariance);
}

std::complex<double> SingleModeFit::DynamicTerm(double a, double omega) const {
  const auto bp = Basis(a, frequency_degree), bq = Basis(a, damping_degree);
  const double omega_n_sq = parameters.segment(1, bp.size()).dot(bp);
  const double zeta_omega = parameters.segment(1 + bp.size(), bq.size()).dot(bq);
  return {omega_n_sq - omega * omega, 2 * omega * zeta_omega};
}

SingleModeFit FitSingleMode(const std::vector<SingleModePoint>& points, const SingleModeFitOptions& options) {
  SingleModeFit fit;
  fit.frequency_degree = options.frequency_degree;
  fit.damping_degree = options.damping_degree;
  fit.reference_amplitude_m = options.reference_amplitude_m;
  const int np = options.frequency_degree + 1, nq = options.damping_degree + 1;
  const int k = 1 + np + nq;
  const int n = 2 * static_cast<int>(points.size());
  fit.num_residuals = n;
  fit.parameters = Eigen::VectorXd::Zero(k);
  fit.covariance = Eigen::MatrixXd::Zero(k, k);
  if (n < k + 2) return fit;

  // Rows: [Re G, −b_p, 0] x = −ω²;  [Im G, 0, −2ω b_q] x = 0.
  Eigen::MatrixXd design = Eigen::MatrixXd::Zero(n, k);
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(n);
  std::vector<Eigen::Matrix2d> g_cov(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    const auto& p = points[i];
    const auto bp = fit.Basis(p.amplitude_m, options.frequency_degree);
    const auto bq = fit.Basis(p.amplitude_m, options.damping_degree);
    design(2 * i, 0) = p.inverse_receptance_N_m.real();
    design.block(2 * i, 1, 1, np) = -bp.transpose();
    rhs[2 * i] = -p.omega_rad_s * p.omega_rad_s;
    design(2 * i + 1, 0) = p.inverse_receptance_N_m.imag();
    design.block(2 * i + 1, 1 + np, 1, nq) = -2 * p.omega_rad_s * bq.transpose();
    g_cov[i] = p.inverse_receptance_covariance;
    if (g_cov[i].trace() <= 0)
      g_cov[i] = Eigen::Matrix2d::Identity() * std::pow(options.default_relative_std * std::abs(p.inverse_receptance_N_m), 2);
  }
  // Column scaling for conditioning; A starts from the unweighted solution.
  const Eigen::VectorXd scale = design.colwise().norm().cwiseMax(1e-300).cwiseInverse();
  auto solve = [&](const Eigen::MatrixXd& a, const Eigen::VectorXd& b) -> Eigen::VectorXd {
    return scale.asDiagonal() * Eigen::ColPivHouseholderQR<Eigen::MatrixXd>(a * scale.asDiagonal()).solve(b);
  };
  Eigen::VectorXd x = solve(design, rhs);
  Eigen::MatrixXd whitened_design = design;
  Eigen::VectorXd whitened_rhs = rhs;
  for (int iteration = 0; iteration <= options.reweighting_iterations; ++iteration) {
    for (std::size_t i = 0; i < points.size(); ++i) {
      Eigen::Matrix2d cov = x[0] * x[0] * g_cov[i];
      cov(0, 0) += std::pow(2 * points[i].omega_rad_s * points[i].omega_std_rad_s, 2);
      // Inverse of the Cholesky factor L of the pair's covariance, by hand for 2×2.
      const double l11 = std::sqrt(cov(0, 0)), l21 = cov(1, 0) / l11;
      const double l22 = std::sqrt(std::max(cov(1, 1) - l21 * l21, 1e-30 * cov(1, 1)));
      Eigen::Matrix2d l_inverse;
      l_inverse << 1 / l11, 0, -l21 / (l11 * l22), 1 / l22;
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
  fit.covariance = scale.asDiagonal() * normal_inverse * scale.asDiagonal();
  fit.covariance *= std::max(1.0, fit.ReducedChiSquare());
  fit.aicc = n * std::log(std::max(fit.chi_square, 1e-300) / n) + 2.0 * k + 2.0 * k * (k + 1) / std::max(1, n - k - 1);
  const Eigen::VectorXd unweighted = design * x - rhs;
  double sum_sq = 0.0;
  for (int i = 0; i < n; i += 2) sum_sq += unweighted[i] * unweighted[i];
  fit.backbone_residual_rms_rad2_s2 = std::sqrt(sum_sq / (n / 2));
  fit.ok = std::isfinite(fit.chi_square) && fit.parameters.allFinite();
  return fit;
}

}  // namespace beamid::solver
