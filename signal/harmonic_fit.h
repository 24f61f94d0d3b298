// Least-squares multi-harmonic fit of every channel of a segment at a known
// fundamental frequency f (signal/frequency_estimator.h), with the standard
// uncertainty of each phasor from the measured noise floor:
//     x_c(τ_n) = X_0 + Σ_{k=1..H} Re(X_k e^{ikωτ_n}) + e_n,
//     τ_n = (n − (N−1)/2)/f_s   (time origin at the segment centre).
// Coefficients [X_0, a_k, b_k] = (BᵀB)⁻¹Bᵀx, X_k = a_k − i·b_k (peak
// phasors, docs/fourier-convention.md). No window and no integer number of
// periods is needed: the regression is exact for any record length.
//
// Uncertainty: cov(a_k, b_k) = σ_k²·[(BᵀB)⁻¹]_kk, where σ_k² is the noise
// floor near harmonic k, read from the Hann-windowed periodogram of the
// residual, P_j = |Σ w_n r_n e^{−2πijn/N}|²/Σw_n² (= σ² for white noise),
// averaged over the bins within ±max(f/2, 16 bins) of k·f that lie at least
// 3 bins from every multiple of f (unmodelled harmonics are not noise). So
// coloured noise gives each harmonic its own floor. The cross-covariances
// between harmonics, O(1/N) relative, are neglected.
// The floor is itself an estimate, from ν_k effective degrees of freedom
// (M bins whose Hann periodogram values correlate as 4/9 between
// neighbours and 1/36 two apart: ν = 2M²/(M + 2·(4/9)·n₁ + 2·(1/36)·n₂),
// n₁, n₂ the pairs of used bins one and two apart; ~30 for a 0.5 s record
// at 55 Hz). A phasor's error over σ̂_k is then Student-t, whose variance is
// ν/(ν − 2), not 1: the stated covariance is σ̂_k²·ν/(ν − 2)·[(BᵀB)⁻¹]_kk,
// the standard uncertainty of GUM Supplement 1 for a Type A estimate, so
// that residuals whitened by it have unit mean square (with σ̂_k² alone a
// fit's reduced χ² reads ~1.05 on data its model holds).
#pragma once

#include <complex>
#include <vector>

#include <Eigen/Core>

namespace beamid::signal {

struct ChannelFit {
  double mean = 0.0;                         // X_0
  Eigen::VectorXcd phasors;                  // X_k at index k−1 (k = 1..H), origin at the segment centre
  std::vector<Eigen::Matrix2d> covariances;  // of (Re X_k, Im X_k), same index
  Eigen::VectorXd noise_variance;            // σ̂_k², same index [unit²]
  Eigen::VectorXd noise_dof;                 // ν_k of σ̂_k², same index
  double residual_rms = 0.0;                 // over the whole band
};

struct HarmonicFit {
  double frequency_hz = 0.0;
  int num_harmonics = 0;  // H actually fitted (reduced below Nyquist if needed)
  std::vector<ChannelFit> channels;  // one per column of samples
};

// ν/(ν − 2): a phasor's variance over the noise floor σ̂² estimated with ν
// degrees of freedom (header); 3 below ν = 3, where the floor rests on a
// handful of bins.
double StudentVarianceFactor(double dof);

// samples: one column per channel. Harmonics above Nyquist are left out
// (num_harmonics of the result says how many were fitted).
HarmonicFit FitHarmonics(const Eigen::Ref<const Eigen::MatrixXd>& samples, double sample_rate_hz,
                         double frequency_hz, int num_harmonics);

}  // namespace beamid::signal
