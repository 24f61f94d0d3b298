// The reported standard uncertainties of the phase-referenced phasors match
// the Monte Carlo scatter within 20 %, including the share of the force
// phase used as reference (a noisy force makes it dominant for the response
// fundamentals: the test fails if it is left out).
#include <cmath>
#include <cstdio>
#include <random>

#include <gtest/gtest.h>

#include "signal/phasor_estimator.h"
#include "tests/signal/synthetic_signal.h"

namespace beamid::signal {
namespace {

using testing::RandomTone;
using testing::Synthesize;
using testing::SyntheticCampaign;
using testing::SyntheticRecording;
using testing::Tone;

constexpr int kRuns = 400;  // std of a sample std ≈ 1/√(2·400) = 3.5 %
constexpr double kTolerance = 0.2;

TEST(PhasorUncertaintyTest, ReportedStdMatchesScatterOfReferencedPhasors) {
  const double rate_hz = 5120.0;
  const int n = 3000;
  const double frequency_hz = 63.7;
  const std::vector<double> noise_rel{0.05, 0.002, 0.01};  // force noisiest
  std::mt19937 rng(99);
  Campaign campaign = SyntheticCampaign(2, 63.5);
  std::vector<Tone> tones;
  Eigen::MatrixXd clean(n, 3);
  for (int c = 0; c < 3; ++c) {
    tones.push_back(RandomTone(rng, 5, frequency_hz, 1.0 + c));
    tones.back().sample_rate_hz = rate_hz;
    clean.col(c) = Synthesize(tones.back(), n);
  }
  std::normal_distribution<double> normal;
  // Per channel and harmonic: sums for the scatter of Re and Im, and the mean reported variance.
  Eigen::ArrayXXd sum_re = Eigen::ArrayXXd::Zero(3, 5), sum_im = sum_re, sum2_re = sum_re, sum2_im = sum_re;
  Eigen::ArrayXXd reported_re = sum_re, reported_im = sum_re;
  Eigen::MatrixXd x(n, 3);
  for (int run = 0; run < kRuns; ++run) {
    for (int c = 0; c < 3; ++c)
      for (int i = 0; i < n; ++i) x(i, c) = clean(i, c) + noise_rel[static_cast<std::size_t>(c)] * (1.0 + c) * normal(rng);
    const StepPhasors step = EstimateStepPhasors(SyntheticRecording(campaign, x, rate_hz), campaign, campaign.steps[0]);
    ASSERT_EQ(step.quality.settled_after_s, 0.0) << step.quality.settling;
    for (int c = 0; c < 3; ++c) {
      const ChannelPhasors& channel = c == 0 ? step.force : step.responses[static_cast<std::size_t>(c - 1)];
      for (int k = 1; k <= 5; ++k) {
        const HarmonicPhasor& h = channel.Harmonic(k);
        sum_re(c, k - 1) += h.value.real();
        sum2_re(c, k - 1) += h.value.real() * h.value.real();
        sum_im(c, k - 1) += h.value.imag();
        sum2_im(c, k - 1) += h.value.imag() * h.value.imag();
        reported_re(c, k - 1) += h.std_real * h.std_real / kRuns;
        reported_im(c, k - 1) += h.std_imag * h.std_imag / kRuns;
      }
    }
  }
  auto scatter = [](double sum, double sum2) { return std::sqrt((sum2 - sum * sum / kRuns) / (kRuns - 1)); };
  for (int c = 0; c < 3; ++c) {
    for (int k = 1; k <= 5; ++k) {
      const double ratio_re = std::sqrt(reported_re(c, k - 1)) / scatter(sum_re(c, k - 1), sum2_re(c, k - 1));
      std::printf("channel %d k=%d reported/scatter Re %.3f", c, k, ratio_re);
      EXPECT_NEAR(ratio_re, 1.0, kTolerance) << "channel " << c << " k=" << k;
      if (c == 0 && k == 1) {  // Im F_1 = 0 by construction
        EXPECT_EQ(reported_im(c, k - 1), 0.0);
        std::printf("\n");
        continue;
      }
      const double ratio_im = std::sqrt(reported_im(c, k - 1)) / scatter(sum_im(c, k - 1), sum2_im(c, k - 1));
      std::printf("  Im %.3f\n", ratio_im);
      EXPECT_NEAR(ratio_im, 1.0, kTolerance) << "channel " << c << " k=" << k;
    }
  }
}

}  // namespace
}  // namespace beamid::signal
