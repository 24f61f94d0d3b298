#include "solver/estimation/phasor_uncertainty.h"

#include <cmath>

namespace beamid::solver {
namespace {

Eigen::Vector2d Parts(std::complex<double> z) { return {z.real(), z.imag()}; }

// σ (rms of the real and imaginary parts) of a covariance.
double RmsStd(const Eigen::Matrix2d& covariance) { return std::sqrt(0.5 * covariance.trace()); }

}  // namespace

Eigen::Matrix2d PhasorCovariance(const MeasuredPhasor& phasor, int harmonic, double force_relative_std,
                                 std::complex<double> neighbour_slope, double omega_std_rad_s,
                                 double relative_model_error, double numerical_floor_std,
                                 PhasorUncertaintyBudget* budget) {
  const Eigen::Vector2d y = Parts(phasor.value);
  const Eigen::Vector2d g = Parts(neighbour_slope);
  const double force_scale = harmonic * force_relative_std;
  const Eigen::Matrix2d force = force_scale * force_scale * y * y.transpose();
  const Eigen::Matrix2d frequency = omega_std_rad_s * omega_std_rad_s * g * g.transpose();
  const double model_std = relative_model_error * std::abs(phasor.value);
  const Eigen::Matrix2d model = model_std * model_std * Eigen::Matrix2d::Identity();
  const Eigen::Matrix2d floor = numerical_floor_std * numerical_floor_std * Eigen::Matrix2d::Identity();
  if (budget) {
    budget->noise = RmsStd(phasor.noise_covariance);
    budget->force = RmsStd(force);
    budget->frequency = RmsStd(frequency);
    budget->model_error = RmsStd(model);
  }
  return phasor.noise_covariance + force + frequency + model + floor;
}

std::complex<double> NeighbourSlope(const std::vector<double>& omega_rad_s,
                                    const std::vector<std::complex<double>>& values,
                                    const std::vector<double>& noise_std, std::size_t i) {
  std::vector<std::size_t> around{i};
  for (const std::ptrdiff_t offset : {-1, 1}) {
    const std::ptrdiff_t j = static_cast<std::ptrdiff_t>(i) + offset;
    if (j < 0 || j >= static_cast<std::ptrdiff_t>(values.size())) continue;
    // Repeated frequencies (a sweep that turns, a dwell) have no slope.
    if (!(std::abs(omega_rad_s[j] - omega_rad_s[i]) > 1e-9 * std::abs(omega_rad_s[i]))) continue;
    around.push_back(static_cast<std::size_t>(j));
  }
  const std::complex<double> y = values[i];
  if (around.size() < 2) return 0.0;
  bool resolved = true;
  // (A value of exactly 0, noise-free data's missing harmonic, has no 1/Y.)
  for (const std::size_t j : around)
    resolved = resolved && std::abs(values[j]) > 10.0 * noise_std[j] && std::abs(values[j]) > 0.0;
  if (!resolved) {
    // 1/Y of a harmonic at the noise is noise; its chords are as good as any.
    std::complex<double> smallest = (values[around[1]] - y) / (omega_rad_s[around[1]] - omega_rad_s[i]);
    if (around.size() == 3) {
      const std::complex<double> other = (values[around[2]] - y) / (omega_rad_s[around[2]] - omega_rad_s[i]);
      if (std::abs(other) < std::abs(smallest)) smallest = other;
    }
    return smallest;
  }
  // d(1/Y)/dω from the parabola (two neighbours) or the chord (one) of 1/Y.
  const double w0 = omega_rad_s[i];
  std::complex<double> d_inverse;
  if (around.size() == 2) {
    d_inverse = (1.0 / values[around[1]] - 1.0 / y) / (omega_rad_s[around[1]] - w0);
  } else {
    const double w1 = omega_rad_s[around[1]], w2 = omega_rad_s[around[2]];
    if (!(std::abs(w1 - w2) > 1e-9 * std::abs(w0))) return 0.0;
    d_inverse = (1.0 / y) * ((2.0 * w0 - w1 - w2) / ((w0 - w1) * (w0 - w2))) +
                (1.0 / values[around[1]]) * ((w0 - w2) / ((w1 - w0) * (w1 - w2))) +
                (1.0 / values[around[2]]) * ((w0 - w1) / ((w2 - w0) * (w2 - w1)));
  }
  return -y * y * d_inverse;
}

}  // namespace beamid::solver
