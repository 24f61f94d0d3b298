// A simulated campaign written to disk loads back through signal's strict
// campaign and recording readers (the format's validation), and its files,
// units and truth.json agree with each other.
#include "hb/campaign_writer.h"

#include <cmath>
#include <complex>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "hb/scenario.h"
#include "hb/stepped_sine.h"
#include "hb/time_harmonic_fit.h"
#include "signal/campaign.h"
#include "signal/recording.h"
#include "tests/support/temp_path.h"

namespace beamid::hb {
namespace {

constexpr double kClockPpm = 100.0;

const std::string kScenario = R"({
  "name": "round trip",
  "beam": {"length_m": 0.6, "width_m": 0.04, "thickness_m": 0.005, "youngs_modulus_Pa": 2.0e11,
           "density_kg_m3": 7850, "loss_factor": 0.004},
  "nominal_beam": {"youngs_modulus_Pa": 2.1e11},
  "support": {"polynomial": {"k1_Nm_rad": 150, "k3_Nm_rad3": 3e5, "c_Nms_rad": 0.2}},
  "excitation": {"channel": "F", "position_m": 0.57},
  "sensors": [{"channel": "acc1", "position_m": 0.1},
              {"channel": "vel2", "position_m": 0.3, "quantity": "velocity", "unit": "mm/s"},
              {"channel": "acc3", "position_m": 0.57, "unit": "g", "mass_kg": 0.004}],
  "hidden_positions_m": [0.45],
  "levels": [{"label": "low", "force_amplitude_N": 0.5, "frequencies_Hz": [50.0, 52.0]},
             {"label": "high", "force_amplitude_N": 3.0, "frequencies_Hz": {"start": 51, "stop": 52, "step": 1},
              "direction": "down"}],
  "timing": {"sample_rate_Hz": 4096, "settle_min_s": 0.1, "settle_max_s": 0.4, "transient_s": 0.03, "record_s": 0.25},
  "noise": {"seed": 3, "clock_offset_ppm": 100,
            "default": {"relative_rms": 0.002, "absolute": 0.002, "adc_bits": 24, "adc_range": 400},
            "channels": {"F": {"absolute": 0.001, "adc_bits": 16, "adc_range": 20}}}
})";

class CampaignWriterTest : public ::testing::Test {
 protected:
  void SetUp() override {
    directory_ = beamid::testing::UniqueTempPath("beamid_campaign_writer_test");
    std::filesystem::remove_all(directory_);
  }
  void TearDown() override { std::filesystem::remove_all(directory_); }

  void Simulate(const Scenario& scenario) {
    SteppedSineSimulation simulation(scenario);
    CampaignWriter writer(simulation, directory_);
    simulation.Run([&](const SimulatedStep& step) { writer.Write(step); });
    writer.Finish();
    EXPECT_EQ(writer.clipped_samples(), 0);
  }

  std::filesystem::path directory_;
};

std::complex<double> Harmonic(const nlohmann::json& phasors, int k) {
  const auto& h = phasors.at("harmonics").at(k - 1);
  return {h.at(0).get<double>(), h.at(1).get<double>()};
}

TEST_F(CampaignWriterTest, WrittenCampaignLoadsBackAndMatchesTruth) {
  const Scenario scenario = ParseScenario(kScenario, "round_trip.json");
  Simulate(scenario);

  const signal::Campaign campaign = signal::ReadCampaign(directory_);
  EXPECT_EQ(campaign.name, "round trip");
  EXPECT_EQ(campaign.beam.youngs_modulus_Pa, 2.1e11);  // nominal, not the true 2.0e11
  EXPECT_EQ(campaign.excitation.channel, "F");
  EXPECT_EQ(campaign.excitation.position_m, 0.57);
  ASSERT_EQ(campaign.sensors.size(), 3u);
  EXPECT_EQ(campaign.sensors[1].unit, "mm/s");
  EXPECT_EQ(campaign.sensors[2].unit, "g");
  ASSERT_TRUE(campaign.sensors[2].mass_kg.has_value());
  EXPECT_EQ(*campaign.sensors[2].mass_kg, 0.004);
  EXPECT_FALSE(campaign.sensors[0].mass_kg.has_value());
  ASSERT_TRUE(campaign.sample_rate_hz.has_value());
  EXPECT_EQ(*campaign.sample_rate_hz, 4096.0);
  const std::vector<std::pair<std::string, double>> expected_steps{
      {"low", 50.0}, {"low", 52.0}, {"high", 52.0}, {"high", 51.0}};
  ASSERT_EQ(campaign.steps.size(), expected_steps.size());
  for (size_t i = 0; i < expected_steps.size(); ++i) {
    EXPECT_EQ(campaign.steps[i].level, expected_steps[i].first);
    EXPECT_EQ(campaign.steps[i].frequency_hz, expected_steps[i].second);
  }

  std::ifstream truth_file(directory_ / "truth.json");
  const nlohmann::json truth = nlohmann::json::parse(truth_file);
  EXPECT_EQ(truth.at("beam").at("youngs_modulus_Pa").get<double>(), 2.0e11);
  ASSERT_EQ(truth.at("steps").size(), campaign.steps.size());

  for (size_t i = 0; i < campaign.steps.size(); ++i) {
    SCOPED_TRACE(campaign.steps[i].file);
    const nlohmann::json& step_truth = truth.at("steps").at(i);
    EXPECT_EQ(step_truth.at("file").get<std::string>(), campaign.steps[i].file);
    const double frequency_hz = step_truth.at("frequency_Hz").get<double>();
    EXPECT_NEAR(frequency_hz, campaign.steps[i].frequency_hz * (1 + 1e-6 * kClockPpm), 1e-9);

    const signal::Recording recording = signal::ReadRecording(campaign, campaign.steps[i]);
    EXPECT_EQ(recording.sample_rate_hz, 4096.0);
    const int steady_start = static_cast<int>(std::lround(step_truth.at("steady_start_s").get<double>() * 4096.0));
    EXPECT_EQ(recording.NumSamples(), steady_start + 1024);

    // Fit the steady part of the file (SI after signal's unit conversion) at
    // the true frequency and compare with the noise-free truth.
    TimeHarmonicFit fit(1, 4);
    const double omega = 2 * std::numbers::pi * frequency_hz;
    for (int n = steady_start; n < recording.NumSamples(); ++n) {
      const Eigen::VectorXd row = recording.samples.row(n).transpose();
      fit.Add(omega * n / 4096.0, std::span<const double>(row.data(), 4));
    }
    const std::vector<Eigen::VectorXcd> measured = fit.Solve();
    const std::complex<double> force = measured[0](1);
    const double level_N = step_truth.at("force_amplitude_N").get<double>();
    EXPECT_NEAR(std::abs(force) / level_N, 1.0, 2e-3);
    const char* channels[] = {"acc1", "vel2", "acc3"};
    const double absolute_noise_si[] = {0.002, 0.002e-3, 0.002 * 9.80665};  // 0.002 in each written unit
    for (int c = 0; c < 3; ++c) {
      // Referenced to the force like the truth (docs/fourier-convention.md).
      const std::complex<double> value = measured[c + 1](1) * std::polar(1.0, -std::arg(force));
      const std::complex<double> expected = Harmonic(step_truth.at("channels").at(channels[c]), 1);
      // The least-squares fundamental of N samples with white noise σ has a
      // standard error σ·sqrt(2/N); allow 4 of them.
      const double sigma = 0.002 * std::abs(expected) / std::sqrt(2.0) + absolute_noise_si[c];
      EXPECT_LT(std::abs(value - expected), 4 * sigma * std::sqrt(2.0 / 1024) + 1e-4 * std::abs(expected))
          << channels[c] << ": " << value << " vs " << expected;
    }
    EXPECT_EQ(step_truth.at("hidden").size(), 1u);
  }
}

TEST_F(CampaignWriterTest, RefusesToOverwriteACampaign) {
  Scenario scenario = ParseScenario(kScenario, "round_trip.json");
  scenario.levels.resize(1);
  scenario.levels[0].frequencies_hz.resize(1);
  Simulate(scenario);
  SteppedSineSimulation simulation(scenario);
  EXPECT_THROW(CampaignWriter(simulation, directory_), std::invalid_argument);
  EXPECT_NO_THROW(CampaignWriter(simulation, directory_, {.overwrite = true}));
}

}  // namespace
}  // namespace beamid::hb
