// The multi-harmonic regression basis of a uniformly sampled segment:
//     x(τ_n) ≈ c_0 + Σ_{k=1..H} a_k cos(kωτ_n) + b_k sin(kωτ_n),
//     τ_n = (n − n_0)/f_s,
// columns [1, cos ωτ, sin ωτ, cos 2ωτ, sin 2ωτ, …] (2H+1 of them). With the
// project convention X_k = a_k − i·b_k (docs/fourier-convention.md). n_0 is
// the time origin in samples; the segment centre (N−1)/2 makes the
// amplitude and frequency estimates uncorrelated to first order.
#pragma once

#include <complex>

#include <Eigen/Cholesky>
#include <Eigen/Core>

namespace beamid::signal::internal {

class HarmonicBasis {
 public:
  HarmonicBasis(int num_samples, double sample_rate_hz, double frequency_hz, int num_harmonics,
                double time_origin_sample);
  // Origin at the segment centre.
  HarmonicBasis(int num_samples, double sample_rate_hz, double frequency_hz, int num_harmonics)
      : HarmonicBasis(num_samples, sample_rate_hz, frequency_hz, num_harmonics, 0.5 * (num_samples - 1)) {}

  int num_harmonics() const { return num_harmonics_; }
  double omega_rad_s() const { return omega_rad_s_; }
  const Eigen::MatrixXd& matrix() const { return matrix_; }
  double Tau_s(Eigen::Index n) const { return (static_cast<double>(n) - time_origin_sample_) / sample_rate_hz_; }

  // Least-squares coefficients, one column per column of samples.
  Eigen::MatrixXd Solve(const Eigen::Ref<const Eigen::MatrixXd>& samples) const;
  // (BᵀB)⁻¹: the coefficient covariance per unit noise variance.
  Eigen::MatrixXd InverseNormalMatrix() const;
  const Eigen::LDLT<Eigen::MatrixXd>& normal_factor() const { return normal_; }

  // Phasor X_k of a coefficient column.
  static std::complex<double> Phasor(const Eigen::Ref<const Eigen::VectorXd>& coefficients, int k) {
    return {coefficients(2 * k - 1), -coefficients(2 * k)};
  }

 private:
  int num_harmonics_;
  double sample_rate_hz_;
  double omega_rad_s_;
  double time_origin_sample_;
  Eigen::MatrixXd matrix_;
  Eigen::LDLT<Eigen::MatrixXd> normal_;
};

}  // namespace beamid::signal::internal
