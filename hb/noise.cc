#include "hb/noise.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "hb/internal/pink_noise.h"

namespace beamid::hb {

int MeasurementNoise::Apply(const ChannelNoise& noise, Eigen::Ref<Eigen::VectorXd> samples) {
  if (samples.size() == 0) return 0;
  const double rms = std::sqrt(samples.squaredNorm() / static_cast<double>(samples.size()));
  const double sigma = noise.relative_rms * rms + noise.absolute;
  if (sigma > 0.0) {
    std::normal_distribution<double> gaussian(0.0, sigma);
    for (double& x : samples) x += gaussian(rng_);
  }
  // After the Gaussian draws, so that a channel without drift draws (and
  // writes) exactly what it did before the drift existed.
  internal::AddPinkNoise(noise.pink_rms, rng_, samples);
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
  return Measure(scenario, recording_si, 0, clipped);
}

Eigen::MatrixXd MeasurementNoise::Measure(const Scenario& scenario, const Eigen::MatrixXd& recording_si,
                                          int steady_start_sample, int* clipped) {
  const Eigen::Index rows = recording_si.rows();
  if (steady_start_sample < 0 || steady_start_sample >= std::max<Eigen::Index>(rows, 1))
    throw std::invalid_argument("MeasurementNoise::Measure: steady_start_sample lies outside the recording");
  // 1 + creep·(t/T − 1/2), t/T running from 0 at the first steady sample to
  // 1 at the last: its mean over the steady record is exactly 1.
  Eigen::VectorXd creep;
  const double creep_relative = scenario.amplitude_creep_relative;
  if (creep_relative != 0.0) {
    const double span = static_cast<double>(std::max<Eigen::Index>(rows - 1 - steady_start_sample, 1));
    creep.resize(rows);
    for (Eigen::Index n = 0; n < rows; ++n) creep(n) = 1.0 + creep_relative * ((n - steady_start_sample) / span - 0.5);
  }
  Eigen::MatrixXd written = recording_si;
  for (Eigen::Index c = 0; c < written.cols(); ++c) {
    const bool force = c == 0;
    const ScenarioSensor* sensor = force ? nullptr : &scenario.sensors.at(static_cast<size_t>(c - 1));
    if (sensor && creep.size() > 0) written.col(c).array() *= creep.array();
    if (sensor) written.col(c) /= UnitToSi(sensor->quantity, sensor->unit);
    const int n = Apply(scenario.NoiseOf(force ? scenario.force_channel : sensor->channel), written.col(c));
    if (clipped) *clipped += n;
  }
  return written;
}

}  // namespace beamid::hb
