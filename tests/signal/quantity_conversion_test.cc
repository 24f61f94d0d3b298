// Displacement/velocity/acceleration phasor conversion against time
// derivatives taken numerically from synthesised time series, and the
// covariance's rotation and scaling.
#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "signal/harmonic_fit.h"
#include "signal/quantity_conversion.h"
#include "tests/signal/synthetic_signal.h"

namespace beamid::signal {
namespace {

using testing::RandomTone;
using testing::Synthesize;
using testing::Tone;

// The derivative of a synthesised record by a 4th-order central difference
// in time (step h), fitted: an independent route to the velocity phasors.
TEST(QuantityConversionTest, VelocityAndAccelerationMatchNumericalDerivatives) {
  std::mt19937 rng(21);
  Tone tone = RandomTone(rng, 4, 31.7);
  const int n = 4096;
  const double h_s = 2e-5;  // truncation (4kωh)⁴/30 < 3e-9 relative, round-off < 1e-10
  const double h_samples = h_s * tone.sample_rate_hz;
  const double center = tone.TimeOriginSample(n);
  auto shifted = [&](double s) { return Synthesize(tone, n, center - s * h_samples); };  // x(τ + s·h)
  const Eigen::VectorXd velocity =
      (-shifted(2) + 8.0 * shifted(1) - 8.0 * shifted(-1) + shifted(-2)) / (12.0 * h_s);
  const Eigen::VectorXd acceleration =
      (-shifted(2) + 16.0 * shifted(1) - 30.0 * shifted(0) + 16.0 * shifted(-1) - shifted(-2)) / (12.0 * h_s * h_s);
  const HarmonicFit v = FitHarmonics(velocity, tone.sample_rate_hz, tone.frequency_hz, 4);
  const HarmonicFit a = FitHarmonics(acceleration, tone.sample_rate_hz, tone.frequency_hz, 4);
  const double omega = 2.0 * std::numbers::pi * tone.frequency_hz;
  for (int k = 1; k <= 4; ++k) {
    HarmonicPhasor displacement;
    displacement.harmonic = k;
    displacement.value = tone.phasors[static_cast<std::size_t>(k - 1)];
    const auto to_velocity = ConvertHarmonic(displacement, Quantity::kDisplacement, Quantity::kVelocity, omega);
    const auto to_acceleration =
        ConvertHarmonic(displacement, Quantity::kDisplacement, Quantity::kAcceleration, omega);
    const double scale_v = k * omega * std::abs(displacement.value);
    const double scale_a = k * omega * scale_v;
    EXPECT_LT(std::abs(to_velocity.value - v.channels[0].phasors(k - 1)), 1e-6 * scale_v + 1e-9) << k;
    EXPECT_LT(std::abs(to_acceleration.value - a.channels[0].phasors(k - 1)), 1e-5 * scale_a + 1e-6) << k;
    // And back.
    const auto back = ConvertHarmonic(to_acceleration, Quantity::kAcceleration, Quantity::kDisplacement, omega);
    EXPECT_LT(std::abs(back.value - displacement.value), 1e-12 * std::abs(displacement.value));
  }
}

TEST(QuantityConversionTest, CovarianceRotatesAndScales) {
  HarmonicPhasor phasor;
  phasor.harmonic = 3;
  phasor.value = {1.0, 2.0};
  phasor.std_real = 0.1;
  phasor.std_imag = 0.3;
  phasor.correlation = 0.25;
  const double omega = 10.0;
  // Displacement -> velocity: multiply by i·30, a 90° turn: Re' = −30 Im, Im' = 30 Re.
  const HarmonicPhasor v = ConvertHarmonic(phasor, Quantity::kDisplacement, Quantity::kVelocity, omega);
  EXPECT_NEAR(v.value.real(), -60.0, 1e-12);
  EXPECT_NEAR(v.value.imag(), 30.0, 1e-12);
  EXPECT_NEAR(v.std_real, 30.0 * 0.3, 1e-12);
  EXPECT_NEAR(v.std_imag, 30.0 * 0.1, 1e-12);
  EXPECT_NEAR(v.correlation, -0.25, 1e-12);
  // Displacement -> acceleration: multiply by −900; correlation kept.
  const HarmonicPhasor a = ConvertHarmonic(phasor, Quantity::kDisplacement, Quantity::kAcceleration, omega);
  EXPECT_NEAR(a.std_real, 900.0 * 0.1, 1e-9);
  EXPECT_NEAR(a.std_imag, 900.0 * 0.3, 1e-9);
  EXPECT_NEAR(a.correlation, 0.25, 1e-12);
  EXPECT_NEAR(a.AmplitudeStd() / std::abs(a.value), phasor.AmplitudeStd() / std::abs(phasor.value), 1e-12);
}

TEST(QuantityConversionTest, ChannelConversionRecomputesThdAndRejectsForce) {
  ChannelPhasors channel;
  channel.channel = "acc1";
  channel.quantity = Quantity::kAcceleration;
  channel.mean = 0.2;
  for (int k = 1; k <= 3; ++k) {
    HarmonicPhasor h;
    h.harmonic = k;
    h.value = {1.0 / k, 0.0};
    channel.harmonics.push_back(h);
  }
  const double omega = 5.0;
  const ChannelPhasors displacement = ConvertChannel(channel, Quantity::kDisplacement, omega);
  EXPECT_EQ(displacement.quantity, Quantity::kDisplacement);
  EXPECT_EQ(displacement.mean, 0.0);
  // |D_k| = |A_k|/(kω)² = 1/(k³ω²): THD = √(1/2⁶ + 1/3⁶)·1.
  EXPECT_NEAR(displacement.thd, std::sqrt(std::pow(2.0, -6) + std::pow(3.0, -6)), 1e-12);
  ChannelPhasors force = channel;
  force.quantity = Quantity::kForce;
  EXPECT_THROW(ConvertChannel(force, Quantity::kDisplacement, omega), std::invalid_argument);
}

}  // namespace
}  // namespace beamid::signal
