// Synthetic stepped-sine records for the signal tests, written from the
// definition of the phasor convention (docs/fourier-convention.md) and
// independent of the estimator code: x(τ_n) = X_0 + Σ_k Re(X_k e^{ikωτ_n}),
// τ_n = (n − n_0)/f_s, plus white Gaussian noise. Also the Cramér–Rao bound of
// this model (unknown X_0, X_k and ω) from its Fisher information.
#pragma once

#include <cmath>
#include <complex>
#include <numbers>
#include <random>
#include <vector>

#include <Eigen/Dense>

namespace beamid::signal::testing {

struct Tone {
  double frequency_hz = 50.0;
  double sample_rate_hz = 5120.0;
  double mean = 0.0;
  std::vector<std::complex<double>> phasors;  // X_1..X_H
  double TimeOriginSample(int num_samples) const { return 0.5 * (num_samples - 1); }
};

// Samples n = 0..N−1 with the time origin n_0 (default: the record centre).
inline Eigen::VectorXd Synthesize(const Tone& tone, int num_samples, double origin_sample) {
  Eigen::VectorXd x(num_samples);
  const double omega = 2.0 * std::numbers::pi * tone.frequency_hz;
  for (int n = 0; n < num_samples; ++n) {
    const double tau = (n - origin_sample) / tone.sample_rate_hz;
    double value = tone.mean;
    for (std::size_t k = 1; k <= tone.phasors.size(); ++k)
      value += std::real(tone.phasors[k - 1] * std::exp(std::complex<double>(0.0, k * omega * tau)));
    x(n) = value;
  }
  return x;
}
inline Eigen::VectorXd Synthesize(const Tone& tone, int num_samples) {
  return Synthesize(tone, num_samples, tone.TimeOriginSample(num_samples));
}

// Random tone: fundamental amplitude `amplitude`, harmonics 2..H at random
// levels between -20 and -60 dB of it, uniformly random phases.
inline Tone RandomTone(std::mt19937& rng, int num_harmonics, double frequency_hz, double amplitude = 1.0) {
  std::uniform_real_distribution<double> phase(-std::numbers::pi, std::numbers::pi);
  std::uniform_real_distribution<double> level_db(-60.0, -20.0);
  Tone tone;
  tone.frequency_hz = frequency_hz;
  tone.mean = 0.3 * amplitude;
  for (int k = 1; k <= num_harmonics; ++k) {
    const double a = k == 1 ? amplitude : amplitude * std::pow(10.0, level_db(rng) / 20.0);
    tone.phasors.push_back(std::polar(a, phase(rng)));
  }
  // Make sure the -60 dB floor is represented.
  if (num_harmonics >= 3) tone.phasors.back() = std::polar(amplitude * 1e-3, phase(rng));
  return tone;
}

// Cramér–Rao bound of θ = [X_0, Re X_1, Im X_1, …, Re X_H, Im X_H, ω] for
// white noise of variance σ²: (JᵀJ/σ²)⁻¹, J_n = ∂x(τ_n)/∂θ.
inline Eigen::MatrixXd CramerRaoBound(const Tone& tone, int num_samples, double noise_variance) {
  const int h = static_cast<int>(tone.phasors.size());
  const double omega = 2.0 * std::numbers::pi * tone.frequency_hz;
  Eigen::MatrixXd jacobian(num_samples, 2 * h + 2);
  for (int n = 0; n < num_samples; ++n) {
    const double tau = (n - tone.TimeOriginSample(num_samples)) / tone.sample_rate_hz;
    jacobian(n, 0) = 1.0;
    double d_omega = 0.0;
    for (int k = 1; k <= h; ++k) {
      const std::complex<double> e = std::exp(std::complex<double>(0.0, k * omega * tau));
      jacobian(n, 2 * k - 1) = e.real();   // ∂/∂Re X_k of Re(X e)
      jacobian(n, 2 * k) = -e.imag();      // ∂/∂Im X_k
      d_omega += std::real(std::complex<double>(0.0, k * tau) * tone.phasors[static_cast<std::size_t>(k - 1)] * e);
    }
    jacobian(n, 2 * h + 1) = d_omega;
  }
  const Eigen::MatrixXd fisher = jacobian.transpose() * jacobian / noise_variance;
  return fisher.inverse();
}

// Delta-method bounds of amplitude and phase of harmonic k from the CRB.
inline double AmplitudeBound(const Eigen::MatrixXd& crb, std::complex<double> x, int k) {
  Eigen::Vector2d g(x.real() / std::abs(x), x.imag() / std::abs(x));
  return g.dot(crb.block<2, 2>(2 * k - 1, 2 * k - 1) * g);
}
inline double PhaseBound(const Eigen::MatrixXd& crb, std::complex<double> x, int k) {
  Eigen::Vector2d g(-x.imag() / std::norm(x), x.real() / std::norm(x));
  return g.dot(crb.block<2, 2>(2 * k - 1, 2 * k - 1) * g);
}

// Wraps a phase difference into (−π, π].
inline double WrapPhase(double phase_rad) { return std::remainder(phase_rad, 2.0 * std::numbers::pi); }

}  // namespace beamid::signal::testing

#include "signal/campaign.h"
#include "signal/recording.h"

namespace beamid::signal::testing {

// A campaign in memory: force "force" and sensors "acc1".."accN".
inline Campaign SyntheticCampaign(int num_sensors, double nominal_frequency_hz) {
  Campaign campaign;
  campaign.name = "synthetic";
  campaign.beam = {0.6, 0.04, 0.005, 2.1e11, 7850.0};
  campaign.excitation = {"force", 0.57, Quantity::kForce, "N", 1.0, std::nullopt};
  for (int s = 1; s <= num_sensors; ++s)
    campaign.sensors.push_back({"acc" + std::to_string(s), 0.1 * s, Quantity::kAcceleration, "m/s^2", 1.0, std::nullopt});
  campaign.steps.push_back({"step.csv", nominal_frequency_hz, "low"});
  return campaign;
}

// A recording in memory from one column per channel.
inline Recording SyntheticRecording(const Campaign& campaign, const Eigen::MatrixXd& samples, double sample_rate_hz) {
  Recording recording;
  recording.file = "synthetic.csv";
  for (const auto* channel : campaign.Channels()) recording.channels.push_back(channel->channel);
  recording.sample_rate_hz = sample_rate_hz;
  recording.samples = samples;
  return recording;
}

}  // namespace beamid::signal::testing
