#include "signal/quantity_conversion.h"

#include <cmath>
#include <numbers>
#include <stdexcept>

namespace beamid::signal {

std::complex<double> DerivativeFactor(int harmonic, double omega_rad_s, int order) {
  if (harmonic < 1 || !(omega_rad_s > 0.0))
    throw std::invalid_argument("DerivativeFactor needs a harmonic >= 1 and a positive angular frequency");
  return std::polar(std::pow(harmonic * omega_rad_s, order), order * 0.5 * std::numbers::pi);
}

HarmonicPhasor ConvertHarmonic(const HarmonicPhasor& phasor, Quantity from, Quantity to, double omega_rad_s) {
  const int order = DerivativeOrder(to) - DerivativeOrder(from);
  const std::complex<double> factor = DerivativeFactor(phasor.harmonic, omega_rad_s, order);
  HarmonicPhasor result = phasor;
  result.value = phasor.value * factor;
  const double angle = std::arg(factor);
  Eigen::Matrix2d rotation;
  rotation << std::cos(angle), -std::sin(angle), std::sin(angle), std::cos(angle);
  result.SetCovariance(std::norm(factor) * rotation * phasor.Covariance() * rotation.transpose());
  return result;
}

ChannelPhasors ConvertChannel(const ChannelPhasors& channel, Quantity to, double omega_rad_s) {
  ChannelPhasors result = channel;
  result.quantity = to;
  result.mean = 0.0;
  result.noise_rms = 0.0;
  double harmonic_power = 0.0;
  for (auto& phasor : result.harmonics) {
    phasor = ConvertHarmonic(phasor, channel.quantity, to, omega_rad_s);
    if (phasor.harmonic >= 2) harmonic_power += std::norm(phasor.value);
  }
  const double fundamental = result.harmonics.empty() ? 0.0 : std::abs(result.harmonics.front().value);
  result.thd = fundamental > 0.0 ? std::sqrt(harmonic_power) / fundamental : 0.0;
  return result;
}

}  // namespace beamid::signal
