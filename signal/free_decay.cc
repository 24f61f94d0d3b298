#include "signal/free_decay.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>
#include <utility>

#include <Eigen/Cholesky>
#include <Eigen/QR>

#include "hb/option_checks.h"

namespace beamid::signal {

void FreeDecayOptions::Validate() const {
  using namespace option_checks;
  RequireInRange("FreeDecayOptions.periods_per_window", periods_per_window, 2.0, 1000.0);
  RequireInRange("FreeDecayOptions.skip_periods", skip_periods, 0.0, 1000.0);
  RequireAbove("FreeDecayOptions.min_snr", min_snr, 1.0);
  RequireAtLeast("FreeDecayOptions.min_windows", min_windows, 1);
}

namespace {

// σ [1/s] and ω_d [rad/s] of a ring-down.
struct Pole {
  double decay_rate = 0.0;
  double omega = 0.0;
};

// The ringing frequency of a window to start from: the largest projection
// |Σ (x_n − x̄)·e^{−iωτ_n}| over ±30 % of the drive, on a grid of a quarter of
// the window's resolution. A two-pole linear prediction, exact on one mode,
// is pulled far off by the higher modes a switch-off starts.
double StrongestFrequency(const Eigen::Ref<const Eigen::VectorXd>& x, double fs, double omega_guess) {
  const Eigen::Index n = x.size();
  const Eigen::ArrayXd centred = x.array() - x.mean();
  const Eigen::ArrayXd tau = Eigen::ArrayXd::LinSpaced(n, 0.0, static_cast<double>(n - 1)) / fs;
  const double resolution = 2.0 * std::numbers::pi * fs / static_cast<double>(n);
  const int half = static_cast<int>(std::ceil(0.3 * omega_guess / (0.25 * resolution)));
  double best = omega_guess, best_power = -1.0;
  for (int k = -half; k <= half; ++k) {
    const double omega = omega_guess + 0.25 * resolution * k;
    const double c = (centred * (omega * tau).cos()).sum(), s = (centred * (omega * tau).sin()).sum();
    if (c * c + s * s > best_power) best_power = c * c + s * s, best = omega;
  }
  return best;
}

struct WindowFit {
  Pole pole;
  double a = 0.0, b = 0.0, offset = 0.0;
  double residual_rms = 0.0;
  Eigen::Matrix<double, 5, 5> covariance;  // of (a, b, c, σ, ω)
};

// Gauss–Newton with a Levenberg safeguard on the window's samples, time from
// its centre. nullopt when it does not converge to a finite ring-down.
std::optional<WindowFit> FitWindow(const Eigen::Ref<const Eigen::VectorXd>& x, double fs, Pole start) {
  const Eigen::Index n = x.size();
  const Eigen::VectorXd tau =
      (Eigen::VectorXd::LinSpaced(n, 0.0, static_cast<double>(n - 1)).array() - 0.5 * static_cast<double>(n - 1)) / fs;
  Eigen::Matrix<double, 5, 1> p;
  const auto residual_and_jacobian = [&](const Eigen::Matrix<double, 5, 1>& q, Eigen::VectorXd& r,
                                         Eigen::MatrixXd* jacobian) {
    const Eigen::ArrayXd envelope = (-q(3) * tau.array()).exp();
    const Eigen::ArrayXd cosine = (q(4) * tau.array()).cos(), sine = (q(4) * tau.array()).sin();
    const Eigen::ArrayXd ringing = envelope * (q(0) * cosine + q(1) * sine);
    r = x.array() - ringing - q(2);
    if (!jacobian) return;
    jacobian->resize(n, 5);
    jacobian->col(0) = envelope * cosine;
    jacobian->col(1) = envelope * sine;
    jacobian->col(2).setOnes();
    jacobian->col(3) = -tau.array() * ringing;
    jacobian->col(4) = tau.array() * envelope * (q(1) * cosine - q(0) * sine);
  };
  // The amplitudes at the start pole: linear least squares.
  {
    Eigen::VectorXd r;
    Eigen::MatrixXd j;
    p << 0.0, 0.0, 0.0, start.decay_rate, start.omega;
    residual_and_jacobian(p, r, &j);
    p.head<3>() = j.leftCols<3>().colPivHouseholderQr().solve(x);
  }
  Eigen::VectorXd r;
  Eigen::MatrixXd j;
  residual_and_jacobian(p, r, &j);
  double cost = r.squaredNorm();
  double lambda = 1e-6;
  for (int iteration = 0; iteration < 100; ++iteration) {
    const Eigen::Matrix<double, 5, 5> normal = j.transpose() * j;
    const Eigen::Matrix<double, 5, 1> gradient = j.transpose() * r;
    Eigen::Matrix<double, 5, 5> damped = normal;
    damped.diagonal() *= 1.0 + lambda;
    const Eigen::Matrix<double, 5, 1> step = damped.ldlt().solve(gradient);
    const Eigen::Matrix<double, 5, 1> trial = p + step;
    Eigen::VectorXd trial_r;
    residual_and_jacobian(trial, trial_r, nullptr);
    const double trial_cost = trial_r.squaredNorm();
    if (std::isfinite(trial_cost) && trial_cost <= cost) {
      const bool converged = cost - trial_cost <= 1e-14 * cost || step.tail<2>().cwiseAbs().maxCoeff() <=
                                                                      1e-12 * std::max(1.0, std::abs(p(4)));
      p = trial;
      cost = trial_cost;
      residual_and_jacobian(p, r, &j);
      lambda = std::max(lambda / 10.0, 1e-12);
      if (converged) break;
    } else {
      lambda *= 10.0;
      if (lambda > 1e8) break;
    }
  }
  if (!p.allFinite() || p(4) <= 0.0) return std::nullopt;
  WindowFit fit;
  fit.pole = {.decay_rate = p(3), .omega = p(4)};
  fit.a = p(0);
  fit.b = p(1);
  fit.offset = p(2);
  const double dof = static_cast<double>(n - 5);
  fit.residual_rms = std::sqrt(cost / dof);
  const Eigen::Matrix<double, 5, 5> normal = j.transpose() * j;
  fit.covariance = normal.ldlt().solve(Eigen::Matrix<double, 5, 5>::Identity()) * (cost / dof);
  if (!fit.covariance.allFinite()) return std::nullopt;
  return fit;
}

}  // namespace

FreeDecay AnalyseFreeDecay(const Eigen::Ref<const Eigen::VectorXd>& decay, double sample_rate_hz, double start_s,
                           double frequency_hz, std::string channel, const FreeDecayOptions& options) {
  options.Validate();
  const double fs = sample_rate_hz;
  FreeDecay result{.channel = std::move(channel), .start_s = start_s, .points = {}};
  const auto skipped = static_cast<Eigen::Index>(std::lround(options.skip_periods * fs / frequency_hz));
  const auto window_of = [&](double omega) {
    return static_cast<Eigen::Index>(std::lround(options.periods_per_window * 2.0 * std::numbers::pi * fs / omega));
  };
  const double drive = 2.0 * std::numbers::pi * frequency_hz;
  Pole pole{.decay_rate = 0.0, .omega = drive};
  Eigen::Index begin = skipped;
  if (begin + window_of(pole.omega) > decay.size()) return result;
  pole.omega = StrongestFrequency(decay.segment(begin, window_of(pole.omega)), fs, drive);
  result.start_s = start_s + static_cast<double>(begin) / fs;
  for (Eigen::Index length = window_of(pole.omega); begin + length <= decay.size(); length = window_of(pole.omega)) {
    const std::optional<WindowFit> fit = FitWindow(decay.segment(begin, length), fs, pole);
    // A fit that ran off to another mode, or to growth, is no longer this ring-down.
    if (!fit || !(std::abs(fit->pole.omega / drive - 1.0) < 0.5)) break;
    const double amplitude = std::hypot(fit->a, fit->b);
    if (amplitude * std::sqrt(0.5 * static_cast<double>(length)) < options.min_snr * fit->residual_rms) break;
    pole = fit->pole;
    const double sigma = pole.decay_rate, omega = pole.omega;
    const double omega_n2 = omega * omega + sigma * sigma;
    // ζ = σ/√(ω² + σ²): its gradient in (σ, ω).
    const Eigen::Vector2d gradient(omega * omega / std::pow(omega_n2, 1.5), -sigma * omega / std::pow(omega_n2, 1.5));
    const Eigen::Matrix2d pole_covariance = fit->covariance.bottomRightCorner<2, 2>();
    result.points.push_back({
        .time_s = start_s + (static_cast<double>(begin) + 0.5 * static_cast<double>(length - 1)) / fs,
        .amplitude = amplitude,
        .frequency_hz = omega / (2.0 * std::numbers::pi),
        .frequency_std_hz = std::sqrt(pole_covariance(1, 1)) / (2.0 * std::numbers::pi),
        .damping_ratio = sigma / std::sqrt(omega_n2),
        .damping_ratio_std = std::sqrt(gradient.dot(pole_covariance * gradient)),
        .residual_rms = fit->residual_rms,
    });
    begin += length;
  }
  if (static_cast<int>(result.points.size()) < options.min_windows) result.points.clear();
  return result;
}

}  // namespace beamid::signal
