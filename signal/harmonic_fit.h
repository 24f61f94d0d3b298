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
#pragma once

#include <complex>
#include <vector>

#include <Eigen/Core>

namespace beamid::signal {

struct ChannelFit {
  double mean = 0.0;                         // X_0
  Eigen::VectorXcd phasors;                  // X_k at index k−1 (k = 1..H), origin at the segment centre
  std::vector<Eigen::Matrix2d> covariances;  // of (Re X_k, Im X_k), same index
  Eigen::VectorXd noise_variance;            // σ_k², same index [unit²]
  double residual_rms = 0.0;                 // over the whole band
};

struct HarmonicFit {
  double frequency_hz = 0.0;
  int num_harmonics = 0;  // H actually fitted (reduced below Nyquist if needed)
  std::vector<ChannelFit> channels;  // one per column of samples
};

// samples: one column per channel. Harmonics above Nyquist are left out
// (num_harmonics of the result says how many were fitted).
HarmonicFit FitHarmonics(const Eigen::Ref<const Eigen::MatrixXd>& samples, double sample_rate_hz,
                         double frequency_hz, int num_harmonics);

}  // namespace beamid::signal
