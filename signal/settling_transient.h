// The free vibration that a frequency step starts and that a record taken
// too early still holds, fitted out of the phasors instead of left in them.
//
// A settle criterion stops when the change per cycle is small, not when the
// ringing is below the noise of a long record: after a tolerance of 5e-4 the
// ringing is several phasor σ, beats against the drive, and the harmonic
// fit's noise floor cannot see it (it ignores the bins next to each multiple
// of f, where the ringing is). Around a periodic steady state a small
// perturbation decays like the orbit's Floquet modes; in the frame turning
// with the drive the fundamental's complex amplitude relaxes as
//     X_1(τ) = X_1 + e^{−στ}(A e^{iντ} + B e^{−iντ})
// (a linear beam rings at its damped natural frequency ω_d = ω ± ν alone; a
// stiffening support couples the pair; near a fold ν → 0 and the approach
// turns monotone). Each channel c of the analysed part is therefore fitted as
//     x_c(τ) = X_0 + Σ_k Re(X_k e^{ikωτ})                  (signal/harmonic_fit.h)
//            + e^{−στ}[p_c cos(ω₊τ) + q_c sin(ω₊τ) + r_c cos(ω₋τ) + s_c sin(ω₋τ)],
//     ω± = ω ± ν,
// σ and ν shared by the channels (one mode rings), the amplitudes linear
// (variable projection). σ, ν are found on a fine grid over the record's
// one-period averages of the residual brought to baseband, which costs
// microseconds, then the joint fit is made on every sample.
//
// The ringing is kept only where it lowers χ² = Σ_c |residual_c|²/σ_c² (σ_c²
// the channel's noise floor at the fundamental) by more than noise alone
// could over the search: Δχ² > the χ²(dof) quantile at false_alarm/M, dof the
// ringing's columns × the judged channels, M the grid's independent cells.
// Then the judged channels' harmonics come from the joint fit, their covariance
// σ_k²[(MᵀM)⁻¹]_kk including what separating the ringing from the response
// costs (most as ν → 0, where the two look alike).
//
// Not covered: ringing at the drive frequency itself (ν = 0) over a record
// shorter than its decay. A pair of undamped components ω ± ν with small ν
// bends the same way over so short a record, the search may take it, and the
// phasors then miss by more than their covariance (in a trial, 0.5 %
// ringing decaying at 2.5/s over 0.55 s: χ² 65 on two degrees of freedom).
// Hence off by default (PhasorEstimatorOptions::settling_transient).
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "signal/harmonic_fit.h"

namespace beamid::signal {

struct SettlingTransientOptions {
  // Probability that noise alone, on a settled record, is taken for ringing.
  double false_alarm = 1e-3;
  // Throws InputError naming the field when it is outside 1e-12 … 0.5.
  void Validate() const;
};

struct SettlingTransient {
  bool removed = false;           // the ringing was significant and is out of `fit`
  double decay_rate_per_s = 0.0;  // σ
  double beat_hz = 0.0;           // ν/2π
  double chi_square_drop = 0.0;   // Δχ² of the judged channels
  double threshold = 0.0;         // what noise alone exceeds with probability false_alarm
  // The ringing's fundamental-band amplitude at the start of the analysed
  // part over |X_1|, for the judged channel where it is largest, and that
  // channel; channels whose |X_1| is below a tenth of the largest (near a
  // node) are not compared.
  double amplitude_relative = 0.0;
  std::size_t channel = 0;
};

// samples: the analysed part, one column per channel, as fitted into `fit`
// (same frequency and harmonics); judged: the columns whose residuals decide
// (the responses the analysis uses). Where the ringing is significant, the
// judged channels' phasors and covariances in `fit` are replaced by the joint
// fit's; the others (the reference among them) keep theirs.
SettlingTransient RemoveSettlingTransient(const Eigen::Ref<const Eigen::MatrixXd>& samples, double sample_rate_hz,
                                          const std::vector<bool>& judged, HarmonicFit& fit,
                                          const SettlingTransientOptions& options = {});

}  // namespace beamid::signal
