// The free-decay estimator (signal/free_decay.h) on ring-downs written in
// closed form: a damped sine on an offset, exact and under white noise, and
// a decay whose damping changes with amplitude.
#include "signal/free_decay.h"

#include <cmath>
#include <numbers>
#include <random>

#include <gtest/gtest.h>

namespace beamid::signal {
namespace {

constexpr double kFs = 5000.0;

// x(t) = A·e^{−ζω_n t}·cos(ω_d t + φ) + c
Eigen::VectorXd RingDown(double frequency_hz, double zeta, double amplitude, double seconds, double offset = 0.0) {
  const double omega_n = 2.0 * std::numbers::pi * frequency_hz;
  const double omega_d = omega_n * std::sqrt(1.0 - zeta * zeta);
  const auto n = static_cast<Eigen::Index>(seconds * kFs);
  Eigen::VectorXd x(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    const double t = static_cast<double>(i) / kFs;
    x(i) = amplitude * std::exp(-zeta * omega_n * t) * std::cos(omega_d * t + 0.7) + offset;
  }
  return x;
}

TEST(FreeDecay, AnExactRingDownGivesItsDampingAndFrequencyInEveryWindow) {
  for (const double zeta : {1e-4, 0.002, 0.02, 0.1})
    for (const double f : {8.0, 80.2, 1500.0}) {
      // Long enough for a few windows before 1e-6 of the start.
      const double seconds = std::min(3.0, 20.0 / f + 2.0 / (zeta * 2.0 * std::numbers::pi * f));
      const FreeDecay decay = AnalyseFreeDecay(RingDown(f, zeta, 2.0, seconds, 0.3), kFs, 0.0, f * 1.03, "acc");
      ASSERT_GE(decay.points.size(), 2u) << "f " << f << ", ζ " << zeta;
      const double f_d = f * std::sqrt(1.0 - zeta * zeta);
      for (const DecayPoint& p : decay.points) {
        EXPECT_NEAR(p.damping_ratio, zeta, 1e-6 * zeta) << "f " << f << ", ζ " << zeta << ", t " << p.time_s;
        EXPECT_NEAR(p.frequency_hz, f_d, 1e-7 * f);
        // The amplitude at the window's centre is the envelope there.
        EXPECT_NEAR(p.amplitude, 2.0 * std::exp(-zeta * 2.0 * std::numbers::pi * f * p.time_s), 1e-6);
      }
    }
}

TEST(FreeDecay, UnderWhiteNoiseTheStatedSigmaCoversTheTruth) {
  constexpr double kZeta = 0.005, kF = 55.0, kNoise = 0.01;
  std::mt19937_64 random(42);
  std::normal_distribution<double> normal(0.0, kNoise);
  double sum_z2 = 0.0;
  int n = 0, outside = 0;
  for (int r = 0; r < 100; ++r) {
    Eigen::VectorXd x = RingDown(kF, kZeta, 1.0, 4.0);
    for (double& v : x) v += normal(random);
    const FreeDecay decay = AnalyseFreeDecay(x, kFs, 0.0, 54.0, "acc");
    ASSERT_FALSE(decay.points.empty());
    // The decay stops where a window's amplitude falls below 50 of its σ,
    // s/√(N/2) with N = 8 periods of 5000/55 samples: A ≈ 0.019.
    const double window_sigma = kNoise / std::sqrt(0.5 * 8.0 * kFs / kF);
    EXPECT_LT(decay.points.back().amplitude, 1.6 * 50.0 * window_sigma);
    EXPECT_GT(decay.points.back().amplitude, 50.0 * window_sigma);
    for (const DecayPoint& p : decay.points) {
      const double z = (p.damping_ratio - kZeta) / p.damping_ratio_std;
      sum_z2 += z * z;
      outside += std::abs(z) > 1.96;
      ++n;
      EXPECT_NEAR(p.residual_rms, kNoise, 0.2 * kNoise);
    }
  }
  const double rms_z = std::sqrt(sum_z2 / n);
  std::printf("%d windows: rms z %.3f, %d outside the 95 %% interval\n", n, rms_z, outside);
  EXPECT_NEAR(rms_z, 1.0, 0.1);
  EXPECT_LT(outside, 0.08 * n);
}

TEST(FreeDecay, ADampingThatGrowsWithAmplitudeShowsAlongTheDecay) {
  // ζ(A) = ζ0 + κ·A: integrated as dA/dt = −ζ(A)·ω·A period by period.
  constexpr double kF = 60.0, kZeta0 = 0.002, kKappa = 0.01;
  const double omega = 2.0 * std::numbers::pi * kF;
  const auto n = static_cast<Eigen::Index>(3.0 * kFs);
  Eigen::VectorXd x(n);
  double amplitude = 1.0, phase = 0.0;
  for (Eigen::Index i = 0; i < n; ++i) {
    x(i) = amplitude * std::cos(phase);
    const double zeta = kZeta0 + kKappa * amplitude;
    amplitude *= std::exp(-zeta * omega / kFs);
    phase += omega * std::sqrt(1.0 - zeta * zeta) / kFs;
  }
  const FreeDecay decay = AnalyseFreeDecay(x, kFs, 0.0, kF, "acc");
  ASSERT_GE(decay.points.size(), 5u);
  for (const DecayPoint& p : decay.points)
    EXPECT_NEAR(p.damping_ratio, kZeta0 + kKappa * p.amplitude, 0.02 * (kZeta0 + kKappa * p.amplitude))
        << "at amplitude " << p.amplitude;
  EXPECT_GT(decay.points.front().damping_ratio, decay.points.back().damping_ratio + 0.5 * kKappa * 0.5);
}

TEST(FreeDecay, ARecordTooShortOrTooQuietGivesNoPoint) {
  EXPECT_TRUE(AnalyseFreeDecay(RingDown(55.0, 0.005, 1.0, 0.1), kFs, 0.0, 55.0, "acc").points.empty());
  std::mt19937_64 random(1);
  std::normal_distribution<double> normal(0.0, 1.0);
  Eigen::VectorXd noise(20000);
  for (double& v : noise) v = normal(random);
  EXPECT_TRUE(AnalyseFreeDecay(noise, kFs, 0.0, 55.0, "acc").points.empty());
}

}  // namespace
}  // namespace beamid::signal
