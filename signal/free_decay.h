// The free decay a record holds after its excitation stops: the best damping
// estimate such a record holds, independent of the steady-state ones (it
// needs no force, no sweep and no single-mode fit of an FRF).
//
// After the stop the structure rings at its damped natural frequency. One
// mode dominates near the first resonance, and over a window of a few
// periods its ring-down is
//     x(τ) = e^{−σ·τ}·(a·cos ω_d τ + b·sin ω_d τ) + c,   τ from the window's centre,
//     ζ = σ/ω_n,  ω_n = √(ω_d² + σ²),  amplitude √(a² + b²) at the centre.
// The four unknowns a, b, c (linear) and σ, ω_d are fitted by Gauss–Newton on
// every sample of the window, started from the strongest frequency within
// ±30 % of the drive in the first window (undamped) and then from the
// previous window: the ringing mode is the one the step drove. Consecutive windows
// give ζ and f_d against amplitude, as the backbone gives them against the
// steady amplitude: a nonlinear support shows as a trend along the decay.
// Uncertainty: cov = s²·(JᵀJ)⁻¹, s² the window's residual mean square (white
// noise; unmodelled harmonics and higher modes count into s², which widens
// the interval rather than hiding them). The decay stops where the window's
// signal-to-noise ratio A·√(N/2)/s (N samples: the amplitude over its own
// σ) falls below min_snr.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

namespace beamid::signal {

struct FreeDecayOptions {
  double periods_per_window = 8.0;  // of the ringing frequency
  double skip_periods = 2.0;        // after the span's end, for the switching shock to pass
  double min_snr = 50.0;            // A·√(N/2)/s of a window
  int min_windows = 1;
  // Throws InputError naming the field, its value and the allowed range.
  void Validate() const;
};

// One window of the decay.
struct DecayPoint {
  double time_s = 0.0;            // the window's centre, from the record's first sample
  double amplitude = 0.0;         // at the centre, the channel's SI unit
  double frequency_hz = 0.0;      // damped, f_d
  double frequency_std_hz = 0.0;
  double damping_ratio = 0.0;     // ζ
  double damping_ratio_std = 0.0;
  double residual_rms = 0.0;      // s, the channel's SI unit
};

struct FreeDecay {
  std::string channel;
  double start_s = 0.0;            // first sample analysed, from the record's first sample
  std::vector<DecayPoint> points;  // in time order: falling amplitude
};

// `decay`: the samples of one channel from the first undriven sample on;
// `start_s` its time in the record; `frequency_hz` a first guess of the
// ringing (the step's drive frequency). Returns no points when the decay is
// too short or too quiet for one window.
FreeDecay AnalyseFreeDecay(const Eigen::Ref<const Eigen::VectorXd>& decay, double sample_rate_hz, double start_s,
                           double frequency_hz, std::string channel, const FreeDecayOptions& options = {});

}  // namespace beamid::signal
