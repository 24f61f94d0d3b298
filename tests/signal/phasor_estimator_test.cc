// Step-level phasors: phase reference to the force fundamental (checked
// against the definition Z_k = X_k·e^{−ik·arg F_1}), THD and SNR against the
// synthesis, warnings, and the errors for a step without excitation.
#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "signal/input_error.h"
#include "signal/phasor_estimator.h"
#include "tests/signal/synthetic_signal.h"

namespace beamid::signal {
namespace {

using testing::RandomTone;
using testing::Synthesize;
using testing::SyntheticCampaign;
using testing::SyntheticRecording;
using testing::Tone;

constexpr double kRateHz = 5120.0;

struct Scenario {
  std::vector<Tone> tones;  // force first
  Eigen::MatrixXd samples;
};

// Tones defined with the time origin at the first sample (any origin would
// do: the referenced phasors do not depend on it).
Scenario MakeScenario(unsigned seed, double frequency_hz, int num_samples, double noise_rel) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> normal;
  Scenario scenario;
  scenario.samples.resize(num_samples, 3);
  for (int c = 0; c < 3; ++c) {
    Tone tone = RandomTone(rng, 5, frequency_hz, 1.0 + 3.0 * c);
    tone.sample_rate_hz = kRateHz;
    scenario.samples.col(c) = Synthesize(tone, num_samples, 0.0);
    for (int n = 0; n < num_samples; ++n) scenario.samples(n, c) += noise_rel * std::abs(tone.phasors[0]) * normal(rng);
    scenario.tones.push_back(tone);
  }
  return scenario;
}

std::complex<double> Referenced(const Scenario& scenario, int channel, int k) {
  const double phi = std::arg(scenario.tones[0].phasors[0]);
  return scenario.tones[static_cast<std::size_t>(channel)].phasors[static_cast<std::size_t>(k - 1)] *
         std::polar(1.0, -k * phi);
}

TEST(PhasorEstimatorTest, PhasorsAreReferencedToTheForceFundamental) {
  const Campaign campaign = SyntheticCampaign(2, 80.0);
  const Scenario scenario = MakeScenario(5, 80.37, 6000, 0.0);
  const StepPhasors step =
      EstimateStepPhasors(SyntheticRecording(campaign, scenario.samples, kRateHz), campaign, campaign.steps[0]);
  EXPECT_NEAR(step.frequency_hz, 80.37, 1e-9);
  EXPECT_EQ(step.file, "step.csv");
  EXPECT_EQ(step.level, "low");
  EXPECT_EQ(step.nominal_frequency_hz, 80.0);
  EXPECT_EQ(step.force.Harmonic(1).value.imag(), 0.0);
  EXPECT_GT(step.force.Harmonic(1).value.real(), 0.0);
  EXPECT_EQ(step.force.Harmonic(1).std_imag, 0.0);
  ASSERT_EQ(step.responses.size(), 2u);
  for (int c = 0; c < 3; ++c) {
    const ChannelPhasors& channel = c == 0 ? step.force : step.responses[static_cast<std::size_t>(c - 1)];
    EXPECT_EQ(channel.quantity, c == 0 ? Quantity::kForce : Quantity::kAcceleration);
    ASSERT_EQ(channel.harmonics.size(), 5u);
    for (int k = 1; k <= 5; ++k) {
      const std::complex<double> expected = Referenced(scenario, c, k);
      EXPECT_LT(std::abs(channel.Harmonic(k).value - expected), 1e-9 * std::abs(Referenced(scenario, c, 1)))
          << channel.channel << " k=" << k;
    }
    EXPECT_NEAR(channel.mean, scenario.tones[static_cast<std::size_t>(c)].mean, 1e-9);
    // THD from the synthesis.
    double harmonics = 0.0;
    for (int k = 2; k <= 5; ++k) harmonics += std::norm(scenario.tones[static_cast<std::size_t>(c)].phasors[static_cast<std::size_t>(k - 1)]);
    EXPECT_NEAR(channel.thd, std::sqrt(harmonics) / std::abs(scenario.tones[static_cast<std::size_t>(c)].phasors[0]), 1e-9);
  }
  EXPECT_TRUE(step.quality.warnings.empty());
  EXPECT_EQ(step.quality.settled_after_s, 0.0);
  EXPECT_NEAR(step.quality.analysed_duration_s, 6000 / kRateHz, 1e-12);
}

TEST(PhasorEstimatorTest, SnrAndUncertaintyFollowTheNoise) {
  const Campaign campaign = SyntheticCampaign(2, 80.0);
  const double noise_rel = 1e-2;
  const Scenario scenario = MakeScenario(6, 80.37, 6000, noise_rel);
  const StepPhasors step =
      EstimateStepPhasors(SyntheticRecording(campaign, scenario.samples, kRateHz), campaign, campaign.steps[0]);
  for (int c = 0; c < 3; ++c) {
    const ChannelPhasors& channel = c == 0 ? step.force : step.responses[static_cast<std::size_t>(c - 1)];
    double power = 0.0;
    for (const auto& x : scenario.tones[static_cast<std::size_t>(c)].phasors) power += 0.5 * std::norm(x);
    const double noise_variance = std::pow(noise_rel * std::abs(scenario.tones[static_cast<std::size_t>(c)].phasors[0]), 2);
    EXPECT_NEAR(channel.snr_db, 10.0 * std::log10(power / noise_variance), 0.2) << channel.channel;
    // White noise, N samples: σ(Re X_k) ≈ σ·√(2/N) (plus the reference's share for k ≥ 1).
    const double floor = std::sqrt(noise_variance * 2.0 / 6000.0);
    EXPECT_NEAR(channel.Harmonic(3).std_real / floor, 1.0, 0.25) << channel.channel;
  }
  EXPECT_NEAR(step.quality.snr_db, std::min({step.force.snr_db, step.responses[0].snr_db, step.responses[1].snr_db}), 1e-12);
  EXPECT_GT(step.frequency_std_hz, 0.0);
  EXPECT_LT(std::abs(step.frequency_hz - 80.37), 5.0 * step.frequency_std_hz);
}

TEST(PhasorEstimatorTest, WarnsAboutFrequencyFarFromNominalAndLowSnr) {
  const Campaign campaign = SyntheticCampaign(2, 78.0);  // true 80.37 Hz: 3 % off
  Scenario scenario = MakeScenario(7, 80.37, 6000, 0.0);
  std::mt19937 rng(3);
  std::normal_distribution<double> normal;
  for (int n = 0; n < 6000; ++n) scenario.samples(n, 2) += 2.0 * std::abs(scenario.tones[2].phasors[0]) * normal(rng);
  const StepPhasors step =
      EstimateStepPhasors(SyntheticRecording(campaign, scenario.samples, kRateHz), campaign, campaign.steps[0]);
  ASSERT_EQ(step.quality.warnings.size(), 2u);
  EXPECT_NE(step.quality.warnings[0].find("channel 'acc2': SNR"), std::string::npos) << step.quality.warnings[0];
  EXPECT_NE(step.quality.warnings[1].find("from the nominal 78 Hz"), std::string::npos) << step.quality.warnings[1];
}

TEST(PhasorEstimatorTest, StepWithoutExcitationIsAnInputError) {
  const Campaign campaign = SyntheticCampaign(2, 80.0);
  Scenario scenario = MakeScenario(8, 80.37, 6000, 0.0);
  std::mt19937 rng(4);
  std::normal_distribution<double> normal;
  for (int n = 0; n < 6000; ++n) scenario.samples(n, 0) = normal(rng);  // force cable off
  try {
    EstimateStepPhasors(SyntheticRecording(campaign, scenario.samples, kRateHz), campaign, campaign.steps[0]);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "synthetic.csv");
    EXPECT_EQ(e.channel(), "force");
    EXPECT_NE(std::string(e.what()).find("no excitation near the nominal 80 Hz"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace beamid::signal
