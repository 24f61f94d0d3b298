// Measurement chain of a simulated recording: Gaussian noise per channel
// (σ = relative_rms·RMS(noise-free channel) + absolute) followed by an ADC of
// `adc_bits` over ±adc_range, which rounds to steps of 2·range/2^bits and
// clips beyond the range, as a real acquisition front end does. Quirks of a
// real rig on top: a 1/f drift per channel (ChannelNoise::pink_rms,
// hb/internal/pink_noise.h, added with the Gaussian noise before the ADC)
// and a slow creep of every response channel's amplitude
// (Scenario::amplitude_creep_relative, applied to the signal first).
// Deterministic for a given seed and order of calls (std::mt19937_64).
#pragma once

#include <cstdint>
#include <random>

#include <Eigen/Core>

#include "hb/scenario.h"

namespace beamid::hb {

class MeasurementNoise {
 public:
  explicit MeasurementNoise(std::uint64_t seed) : rng_(seed) {}

  // Applies the noise to one channel's samples (in the unit the channel is
  // written in) and returns how many samples the ADC clipped.
  int Apply(const ChannelNoise& noise, Eigen::Ref<Eigen::VectorXd> samples);

  // A step's noise-free recording (samples × channels: the force, then the
  // sensors in scenario order, SI) as the acquisition writes it: each channel
  // in its written unit with the scenario's noise of that channel applied.
  // Adds the clipped samples to *clipped. The campaign writer uses it, and so
  // can a test that re-noises one clean simulation many times.
  // The amplitude creep is referred to the steady part, which starts at row
  // `steady_start_sample` (SimulatedStep::transient_samples); this form
  // takes the whole recording as steady.
  Eigen::MatrixXd Measure(const Scenario& scenario, const Eigen::MatrixXd& recording_si, int* clipped);
  Eigen::MatrixXd Measure(const Scenario& scenario, const Eigen::MatrixXd& recording_si, int steady_start_sample,
                          int* clipped);

 private:
  std::mt19937_64 rng_;
};

}  // namespace beamid::hb
