// Exact excitation frequency of a stepped-sine record, from the force channel.
//  1. Start: the largest Hann-windowed FFT bin within ±search_band_rel of the
//     nominal frequency, refined by the two-bin Hann interpolation
//     δ = ±(2α − 1)/(α + 1), α = |Y_{m±1}|/|Y_m| (Grandke 1983): a few
//     hundredths of a bin, even with a non-integer number of periods.
//  2. Gauss–Newton on ω of the full multi-harmonic least-squares model
//     x(τ) = c_0 + Σ_k a_k cos kωτ + b_k sin kωτ with the linear coefficients
//     re-solved at each ω (variable projection):
//         Δω = dᵀr / (dᵀ P⊥ d),   d = ∂x/∂ω = Σ_k kτ(−a_k sin kωτ + b_k cos kωτ),
//     r the residual, P⊥ the projector off the basis. At convergence this is
//     the maximum-likelihood estimate in white noise, which reaches the
//     Cramér–Rao bound; its standard uncertainty is σ/√(dᵀP⊥d), σ² the
//     residual variance.
#pragma once

#include <Eigen/Core>

namespace beamid::signal {

struct FrequencyEstimatorOptions {
  int num_harmonics = 5;           // harmonics in the model (all carry frequency information)
  double search_band_rel = 0.05;   // peak search: nominal·(1 ± band), at least ±3 bins
  int max_iterations = 30;
  double tolerance_rel = 1e-12;    // stop when |Δf| < tolerance·f

  // Throws InputError naming the field, its value and the allowed range.
  void Validate() const;
};

struct FrequencyEstimate {
  double frequency_hz = 0.0;
  double std_hz = 0.0;             // standard uncertainty (white-noise model)
  double initial_frequency_hz = 0.0;  // the interpolated-DFT start
  int iterations = 0;
  double fundamental_amplitude = 0.0;  // |X_1| of the force channel
  double fundamental_std = 0.0;        // its standard uncertainty
};

// Interpolated-DFT estimate alone (step 1); throws std::invalid_argument if
// the band holds no bin.
double InterpolatedDftFrequency(const Eigen::Ref<const Eigen::VectorXd>& samples, double sample_rate_hz,
                                double nominal_frequency_hz, double search_band_rel);

// Full estimate (steps 1 and 2). start_frequency_hz > 0 skips step 1 (e.g. a
// previous estimate on an overlapping segment). Throws std::runtime_error if
// Gauss–Newton does not converge.
FrequencyEstimate EstimateFrequency(const Eigen::Ref<const Eigen::VectorXd>& samples, double sample_rate_hz,
                                    double nominal_frequency_hz, const FrequencyEstimatorOptions& options = {},
                                    double start_frequency_hz = 0.0);

}  // namespace beamid::signal
