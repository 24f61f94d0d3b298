#include "signal/phasor_set.h"

#include <cmath>
#include <numbers>
#include <stdexcept>

namespace beamid::signal {

Eigen::Matrix2d HarmonicPhasor::Covariance() const {
  Eigen::Matrix2d covariance;
  const double off = correlation * std_real * std_imag;
  covariance << std_real * std_real, off, off, std_imag * std_imag;
  return covariance;
}

void HarmonicPhasor::SetCovariance(const Eigen::Matrix2d& covariance) {
  std_real = std::sqrt(std::max(0.0, covariance(0, 0)));
  std_imag = std::sqrt(std::max(0.0, covariance(1, 1)));
  correlation = std_real > 0.0 && std_imag > 0.0 ? covariance(0, 1) / (std_real * std_imag) : 0.0;
}

double HarmonicPhasor::AmplitudeStd() const {
  const double a = std::abs(value);
  if (a == 0.0) return std::sqrt(0.5 * (std_real * std_real + std_imag * std_imag));
  const Eigen::Vector2d g(value.real() / a, value.imag() / a);
  return std::sqrt(g.dot(Covariance() * g));
}

double HarmonicPhasor::PhaseStdRad() const {
  const double a2 = std::norm(value);
  if (a2 == 0.0) return std::numbers::pi / std::sqrt(3.0);  // uniform phase
  const Eigen::Vector2d g(-value.imag() / a2, value.real() / a2);
  return std::sqrt(g.dot(Covariance() * g));
}

const HarmonicPhasor& ChannelPhasors::Harmonic(int k) const {
  if (k < 1 || k > static_cast<int>(harmonics.size()))
    throw std::out_of_range("channel '" + channel + "' has harmonics 1.." + std::to_string(harmonics.size()) +
                            ", not " + std::to_string(k));
  return harmonics[static_cast<std::size_t>(k - 1)];
}

double StepPhasors::Omega_rad_s() const { return 2.0 * std::numbers::pi * frequency_hz; }

const ChannelPhasors* StepPhasors::Find(std::string_view channel) const {
  if (force.channel == channel) return &force;
  for (const auto& response : responses)
    if (response.channel == channel) return &response;
  return nullptr;
}

}  // namespace beamid::signal
