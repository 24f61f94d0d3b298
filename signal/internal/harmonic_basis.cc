#include "signal/internal/harmonic_basis.h"

#include <numbers>

namespace beamid::signal::internal {

HarmonicBasis::HarmonicBasis(int num_samples, double sample_rate_hz, double frequency_hz, int num_harmonics,
                             double time_origin_sample)
    : num_harmonics_(num_harmonics),
      sample_rate_hz_(sample_rate_hz),
      omega_rad_s_(2.0 * std::numbers::pi * frequency_hz),
      time_origin_sample_(time_origin_sample),
      matrix_(num_samples, 2 * num_harmonics + 1) {
  for (Eigen::Index n = 0; n < num_samples; ++n) {
    // One sincos per sample; the harmonics by complex powers (error ~k·eps).
    const std::complex<double> e1 = std::polar(1.0, omega_rad_s_ * Tau_s(n));
    std::complex<double> ek = e1;
    matrix_(n, 0) = 1.0;
    for (int k = 1; k <= num_harmonics; ++k) {
      matrix_(n, 2 * k - 1) = ek.real();
      matrix_(n, 2 * k) = ek.imag();
      ek *= e1;
    }
  }
  Eigen::MatrixXd normal = Eigen::MatrixXd::Zero(matrix_.cols(), matrix_.cols());
  normal.selfadjointView<Eigen::Lower>().rankUpdate(matrix_.transpose());
  normal_.compute(normal.selfadjointView<Eigen::Lower>());
}

Eigen::MatrixXd HarmonicBasis::Solve(const Eigen::Ref<const Eigen::MatrixXd>& samples) const {
  return normal_.solve(matrix_.transpose() * samples);
}

Eigen::MatrixXd HarmonicBasis::InverseNormalMatrix() const {
  return normal_.solve(Eigen::MatrixXd::Identity(matrix_.cols(), matrix_.cols()));
}

}  // namespace beamid::signal::internal
