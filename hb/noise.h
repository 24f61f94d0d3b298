// Measurement chain of a simulated recording: Gaussian noise per channel
// (σ = relative_rms·RMS(noise-free channel) + absolute) followed by an ADC of
// `adc_bits` over ±adc_range, which rounds to steps of 2·range/2^bits and
// clips beyond the range, as a real acquisition front end does.
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

 private:
  std::mt19937_64 rng_;
};

}  // namespace beamid::hb
