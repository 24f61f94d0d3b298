// Internal: low-frequency 1/f ("pink") drift of a recorded channel, as the
// slow wander of a sensor's conditioning, a thermal offset or the mains
// hum's neighbours: a random series whose power spectral density falls as
// 1/f over the record's whole band, from its lowest resolvable frequency
// 1/T to (nearly) the Nyquist frequency f_s/2.
//
// Synthesised in the frequency domain over the N samples of one record:
// bin k (frequency k/T, k = 1..⌊N/2⌋ − 1) gets a complex Gaussian amplitude
// of variance ∝ 1/k, and the mean (k = 0) none. The series is then scaled to
// the requested RMS exactly, so that a test (and a scenario author) gets the
// level asked for, not a random one. Deterministic for a given generator
// state: it draws 2·(⌊N/2⌋ − 1) normal numbers from `rng`, in bin order.
#pragma once

#include <random>

#include <Eigen/Core>

namespace beamid::hb::internal {

// Adds pink noise of RMS `rms` (in the samples' unit) to `samples`. Does
// nothing (and draws nothing) for rms = 0 or fewer than 3 samples.
void AddPinkNoise(double rms, std::mt19937_64& rng, Eigen::Ref<Eigen::VectorXd> samples);

}  // namespace beamid::hb::internal
