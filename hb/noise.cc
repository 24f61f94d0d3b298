#include "hb/noise.h"

#include <algorithm>
#include <cmath>

namespace beamid::hb {

int MeasurementNoise::Apply(const ChannelNoise& noise, Eigen::Ref<Eigen::VectorXd> samples) {
  if (samples.size() == 0) return 0;
  const double rms = std::sqrt(samples.squaredNorm() / static_cast<double>(samples.size()));
  const double sigma = noise.relative_rms * rms + noise.absolute;
  if (sigma > 0.0) {
    std::normal_distribution<double> gaussian(0.0, sigma);
    for (double& x : samples) x += gaussian(rng_);
  }
  int clipped = 0;
  if (noise.adc_bits > 0) {
    const double range = noise.adc_range;
    const double step = 2.0 * range / std::ldexp(1.0, noise.adc_bits);
    for (double& x : samples) {
      if (std::abs(x) > range) ++clipped;
      x = std::clamp(std::round(x / step) * step, -range, range);
    }
  }
  return clipped;
}

Eigen::MatrixXd MeasurementNoise::Measure(const Scenario& scenario, const Eigen::MatrixXd& recording_si,
                                          int* clipped) {
  Eigen::MatrixXd written = recording_si;
  for (Eigen::Index c = 0; c < written.cols(); ++c) {
    const bool force = c == 0;
    const ScenarioSensor* sensor = force ? nullptr : &scenario.sensors.at(static_cast<size_t>(c - 1));
    if (sensor) written.col(c) /= UnitToSi(sensor->quantity, sensor->unit);
    const int n = Apply(scenario.NoiseOf(force ? scenario.force_channel : sensor->channel), written.col(c));
    if (clipped) *clipped += n;
  }
  return written;
}

}  // namespace beamid::hb
