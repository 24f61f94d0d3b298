// Where the steady state of a stepped-sine record begins. After a frequency
// step the response holds a decaying transient (free vibration at the
// natural frequencies); only the periodic part that follows represents the
// step. Method:
//  1. Fit the periodic multi-harmonic model (signal/harmonic_fit.h basis) at
//     the step's frequency to the last reference_fraction of the record (at
//     least min_steady_periods), assumed steady, and extend it over the whole
//     record.
//  2. Residual mean square per block of L ≈ one period (32 ≤ L ≤ N/16) for
//     every channel; the noise floor σ² is the median block value inside the
//     reference part (robust to what transient is left there).
//  3. A block is quiet when every channel's mean square stays below
//     σ²·(1 + threshold·√(2/L)) (threshold standard deviations of a
//     white-noise block mean square). The steady state begins at the first
//     block followed by settled_blocks − 1 more quiet blocks: a transient
//     decays monotonically, a later noise spike does not restart it.
//  4. If that point lies inside the reference part, the reference held
//     transient: fit again on what is steady. If the residual's mean square
//     falls by more than max_decay_ratio between the reference's two halves,
//     a slow transient was taken for noise: the reference is halved towards
//     the end of the record. (At most max_passes passes.)
//  5. If that drops more than max_periodic_drop_fraction of the record (or
//     finds no steady part), steps 1–4 run again with a drift model: every
//     basis column also multiplied by the time from the reference's centre,
//     so an amplitude, phase or offset that changes linearly (thermal creep
//     of a few % over a long record, a generator's slow phase walk) is part
//     of the steady response, and the residual minus its one-period moving
//     mean, so low-frequency (1/f) sensor noise is not taken for a
//     transient. A transient, which decays exponentially at the natural
//     frequencies, stays above the noise under that model too. The drift
//     model is kept when it settles earlier; the result then says "steady
//     with drift" and by how much the worst channel changes.
// A record whose steady part is shorter than min_steady_periods raises
// InputError "no steady state" naming the file and the channel.
#pragma once

#include <span>
#include <string>

#include <Eigen/Core>

namespace beamid::signal {

struct SteadyStateOptions {
  double reference_fraction = 0.5;
  double threshold = 6.0;
  int settled_blocks = 3;
  double min_steady_periods = 8.0;
  double max_decay_ratio = 1.5;
  int max_passes = 6;
  // Floor of the noise level relative to the channel's RMS, so that
  // noise-free (simulated) records settle where the transient falls below
  // rounding instead of never.
  double relative_noise_floor = 1e-9;
  // Step 5 runs when the periodic model drops more than this fraction
  // (and not at all without drift_model).
  bool drift_model = true;
  double max_periodic_drop_fraction = 0.5;

  // Throws InputError naming the field, its value and the allowed range.
  void Validate() const;
};

struct SteadyState {
  Eigen::Index first_sample = 0;  // first sample of the steady part
  double settled_after_s = 0.0;   // first_sample / f_s
  std::string reason;             // for the quality record
  // With the drift model (step 5): the largest relative change of a
  // channel's fundamental over the analysed part, and that channel; 0 and
  // empty when the record is steady without drift.
  double drift_relative = 0.0;
  std::string drift_channel;
};

// samples: one column per channel (names in channels, for messages).
SteadyState DetectSteadyState(const Eigen::Ref<const Eigen::MatrixXd>& samples, std::span<const std::string> channels,
                              double sample_rate_hz, double frequency_hz, int num_harmonics, const std::string& file,
                              const SteadyStateOptions& options = {});

}  // namespace beamid::signal
