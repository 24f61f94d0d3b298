// timing.excitation_stop_fraction (docs/simulator.md): the shaker is switched
// off inside every recording. After the stop the written force is only its
// noise, the response rings down, truth.json says when the force stopped,
// and the truth is still the forced steady state (fitted before the stop).
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "hb/scenario.h"
#include "tests/support/csv_text.h"
#include "tests/support/json_file.h"
#include "tests/support/simulated_campaign.h"
#include "tests/support/temp_path.h"

namespace beamid::hb {
namespace {

constexpr double kSampleRate_Hz = 4096.0;
constexpr double kForceNoise_N = 0.002;

std::string ScenarioText(double stop_fraction) {
  return R"({
  "beam": {"length_m": 0.6, "width_m": 0.04, "thickness_m": 0.005, "youngs_modulus_Pa": 2.0e11,
           "density_kg_m3": 7850, "loss_factor": 0.0002},
  "support": {"polynomial": {"k1_Nm_rad": 150, "c_Nms_rad": 0.3}},
  "excitation": {"channel": "force", "position_m": 0.57},
  "sensors": [{"channel": "acc3", "position_m": 0.57}, {"channel": "acc1", "position_m": 0.1}],
  "levels": [{"label": "only", "force_amplitude_N": 1.0, "frequencies_Hz": [53.0, 54.0]}],
  "timing": {"sample_rate_Hz": 4096, "settle_min_s": 0.1, "settle_max_s": 1.0, "settle_tolerance": 1e-4,
             "transient_s": 0.05, "record_s": 0.5, "excitation_stop_fraction": )" +
         std::to_string(stop_fraction) + R"(},
  "noise": {"seed": 7, "default": {"absolute": 0.001}, "channels": {"force": {"absolute": 0.002}}}
})";
}

double Rms(const std::vector<double>& x, size_t begin, size_t end) {
  double sum = 0.0;
  for (size_t i = begin; i < end; ++i) sum += x[i] * x[i];
  return std::sqrt(sum / static_cast<double>(end - begin));
}

// Simulates the scenario into `directory` and returns its truth.json.
nlohmann::json Simulate(const std::string& text, const std::filesystem::path& directory) {
  beamid::testing::SimulateInto(ParseScenario(text, "stop.json"), directory);
  return beamid::testing::ReadJsonFile(directory / "truth.json");
}

class ExcitationStopTest : public ::testing::Test {
 protected:
  void SetUp() override {
    stopped_ = beamid::testing::UniqueTempPath("beamid_stop");
    running_ = beamid::testing::UniqueTempPath("beamid_no_stop");
    std::filesystem::remove_all(stopped_);
    std::filesystem::remove_all(running_);
  }
  void TearDown() override {
    std::filesystem::remove_all(stopped_);
    std::filesystem::remove_all(running_);
  }
  std::filesystem::path stopped_, running_;
};

TEST_F(ExcitationStopTest, ForceIsNoiseAfterTheStopAndTheBeamRingsDown) {
  const nlohmann::json truth = Simulate(ScenarioText(0.8), stopped_);
  ASSERT_EQ(truth.at("steps").size(), 2u);
  for (const nlohmann::json& step : truth.at("steps")) {
    SCOPED_TRACE(step.at("file").get<std::string>());
    const auto columns = beamid::testing::ReadCsvColumns(stopped_ / step.at("file").get<std::string>());
    const std::vector<double>& force = columns.at(1);
    const std::vector<double>& acc3 = columns.at(2);
    const size_t rows = force.size();
    const size_t steady = static_cast<size_t>(std::lround(step.at("steady_start_s").get<double>() * kSampleRate_Hz));

    // truth.json: the stop, at 80 % of the file's duration, inside the steady part.
    ASSERT_TRUE(step.contains("excitation_stop_s"));
    const double stop_s = step.at("excitation_stop_s").get<double>();
    const size_t stop = static_cast<size_t>(std::lround(stop_s * kSampleRate_Hz));
    EXPECT_EQ(stop, static_cast<size_t>(std::lround(0.8 * static_cast<double>(rows))));
    EXPECT_GT(stop, steady + 1000);

    // Before: the 1 N sine (RMS 1/√2). After (the first sample past the stop
    // still holds the ramp to zero): the channel's noise alone.
    EXPECT_NEAR(Rms(force, steady, stop), 1.0 / std::sqrt(2.0), 0.01);
    const double force_after = Rms(force, stop + 2, rows);
    EXPECT_GT(force_after, 0.8 * kForceNoise_N);
    EXPECT_LT(force_after, 1.2 * kForceNoise_N);

    // The response rings down: still large right after the stop, and
    // decaying through the rest of the file.
    const size_t quarter = (rows - stop) / 4;
    const double forced = Rms(acc3, steady, stop);
    const double early = Rms(acc3, stop, stop + quarter);
    const double late = Rms(acc3, rows - quarter, rows);
    EXPECT_GT(early, 0.3 * forced);
    EXPECT_LT(late, 0.85 * early);
  }

  // The truth is the forced steady state: the same as without a stop.
  const nlohmann::json reference = Simulate(ScenarioText(0.0), running_);
  for (size_t i = 0; i < 2; ++i) {
    const nlohmann::json& a = truth.at("steps").at(i);
    const nlohmann::json& b = reference.at("steps").at(i);
    EXPECT_FALSE(b.contains("excitation_stop_s"));
    const auto& ha = a.at("channels").at("acc3").at("harmonics").at(0);
    const auto& hb = b.at("channels").at("acc3").at("harmonics").at(0);
    const double magnitude = std::hypot(hb.at(0).get<double>(), hb.at(1).get<double>());
    EXPECT_NEAR(ha.at(0).get<double>(), hb.at(0).get<double>(), 1e-4 * magnitude);
    EXPECT_NEAR(ha.at(1).get<double>(), hb.at(1).get<double>(), 1e-4 * magnitude);
  }
  EXPECT_EQ(truth.at("excitation").at("stop_fraction").get<double>(), 0.8);
  EXPECT_FALSE(reference.at("excitation").contains("stop_fraction"));
}

}  // namespace
}  // namespace beamid::hb
