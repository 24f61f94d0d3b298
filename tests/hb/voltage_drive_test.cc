// excitation.quantity "voltage" (docs/simulator.md): the level's amplitude is
// the amplifier's input voltage V0, the excitation channel records it in V,
// and the beam feels g(f)·V0 with g sagging near the first resonance. The
// response must be the one of a force drive with that force; campaign.json
// names the voltage channel and g0; truth.json keeps the true force.
#include <cmath>
#include <complex>
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "hb/scenario.h"
#include "hb/stepped_sine.h"
#include "tests/support/csv_text.h"
#include "tests/support/json_file.h"
#include "tests/support/simulated_campaign.h"
#include "tests/support/temp_path.h"

namespace beamid::hb {
namespace {

constexpr double kGain_N_per_V = 10.0;
constexpr double kSag = 0.3;
constexpr double kVoltage_V = 0.15;

const std::string kScenario = R"({
  "beam": {"length_m": 0.6, "width_m": 0.04, "thickness_m": 0.005, "youngs_modulus_Pa": 2.0e11,
           "density_kg_m3": 7850, "loss_factor": 0.0002},
  "support": {"polynomial": {"k1_Nm_rad": 150, "k3_Nm_rad3": 3e5, "c_Nms_rad": 0.1}},
  "excitation": {"channel": "drive", "position_m": 0.57, "quantity": "voltage",
                 "amplifier_gain_N_per_V": 10, "amplifier_sag": 0.3,
                 "distortion": [{"harmonic": 2, "amplitude_ratio": 0.05, "phase_rad": 0.3}]},
  "sensors": [{"channel": "acc3", "position_m": 0.57}],
  "levels": [{"label": "near", "voltage_amplitude_V": 0.15, "frequencies_Hz": [54.0]},
             {"label": "off", "voltage_amplitude_V": 0.15, "frequencies_Hz": [60.0]}],
  "timing": {"sample_rate_Hz": 4096, "settle_min_s": 0.1, "settle_max_s": 1.5, "settle_tolerance": 1e-6,
             "transient_s": 0.05, "record_s": 0.4}
})";

std::complex<double> Harmonic(const nlohmann::json& phasors, int k) {
  const auto& h = phasors.at("harmonics").at(k - 1);
  return {h.at(0).get<double>(), h.at(1).get<double>()};
}

using beamid::testing::ReadJsonFile;
using beamid::testing::SimulateInto;

class VoltageDriveTest : public ::testing::Test {
 protected:
  void SetUp() override {
    voltage_ = beamid::testing::UniqueTempPath("beamid_voltage");
    force_ = beamid::testing::UniqueTempPath("beamid_voltage_as_force");
    std::filesystem::remove_all(voltage_);
    std::filesystem::remove_all(force_);
  }
  void TearDown() override {
    std::filesystem::remove_all(voltage_);
    std::filesystem::remove_all(force_);
  }
  std::filesystem::path voltage_, force_;
};

TEST_F(VoltageDriveTest, RecordsTheVoltageAndDrivesTheSaggedForce) {
  Scenario scenario = ParseScenario(kScenario, "voltage.json");
  // One step at the true f1 (where the gain dips by the full sag) and one
  // 5 band-widths above it.
  const double f1_hz = SteppedSineSimulation(scenario).first_natural_frequency_hz();
  ASSERT_GT(f1_hz, 50.0);
  ASSERT_LT(f1_hz, 58.0);
  const double off_hz = f1_hz * (1.0 + 5 * kAmplifierSagBandRelative);
  scenario.levels[0].frequencies_hz = {f1_hz};
  scenario.levels[1].frequencies_hz = {off_hz};
  SimulateInto(scenario, voltage_);

  const nlohmann::json campaign = ReadJsonFile(voltage_ / "campaign.json");
  EXPECT_EQ(campaign.at("excitation"), nlohmann::json::parse(R"({"channel": "drive", "position_m": 0.57,
      "quantity": "voltage", "unit": "V", "sensitivity_N_per_V": 10.0})"));

  const nlohmann::json truth = ReadJsonFile(voltage_ / "truth.json");
  EXPECT_DOUBLE_EQ(truth.at("excitation").at("amplifier").at("sag_center_Hz").get<double>(), f1_hz);
  const double expected_gain[2] = {kGain_N_per_V * (1.0 - kSag), kGain_N_per_V * (1.0 - kSag / 26.0)};
  ASSERT_EQ(truth.at("steps").size(), 2u);
  for (int i = 0; i < 2; ++i) {
    const nlohmann::json& step = truth.at("steps").at(i);
    SCOPED_TRACE(step.at("file").get<std::string>());
    EXPECT_EQ(step.at("voltage_amplitude_V").get<double>(), kVoltage_V);
    EXPECT_NEAR(step.at("force_amplitude_N").get<double>(), expected_gain[i] * kVoltage_V, 1e-12);
    // The recorded channel is the voltage; the true force is kept beside it.
    const nlohmann::json& drive = step.at("channels").at("drive");
    EXPECT_EQ(drive.at("quantity"), "voltage");
    EXPECT_EQ(drive.at("unit"), "V");
    EXPECT_NEAR(std::abs(Harmonic(drive, 1) - kVoltage_V), 0.0, 1e-9);
    EXPECT_NEAR(std::abs(Harmonic(step.at("force_N"), 1) - expected_gain[i] * kVoltage_V), 0.0, 1e-8);
    // The distortion goes through the gain at its own frequency (2f, far from f1).
    const double f2 = 2.0 * step.at("frequency_Hz").get<double>();
    const double detuning = (f2 - f1_hz) / (kAmplifierSagBandRelative * f1_hz);
    const double gain2 = kGain_N_per_V * (1.0 - kSag / (1.0 + detuning * detuning));
    EXPECT_NEAR(std::abs(Harmonic(step.at("force_N"), 2)), gain2 * 0.05 * kVoltage_V, 1e-9);
    EXPECT_NEAR(std::abs(Harmonic(drive, 2)), 0.05 * kVoltage_V, 1e-10);
  }

  // The CSV's excitation column holds volts.
  {
    const std::filesystem::path csv = voltage_ / truth.at("steps").at(0).at("file").get<std::string>();
    EXPECT_EQ(beamid::testing::ReadCsvHeader(csv), "time_s,drive,acc3");
    double peak = 0.0;
    const auto columns = beamid::testing::ReadCsvColumns(csv);
    for (double value : columns.at(1)) peak = std::max(peak, std::abs(value));
    EXPECT_GT(peak, 0.9 * kVoltage_V);
    EXPECT_LT(peak, 1.1 * kVoltage_V);
  }

  // The beam responds as to a force drive with that force (each harmonic at
  // its gain; a force drive's distortion ratio is then g(2f)/g(f)·0.05).
  for (int i = 0; i < 2; ++i) {
    Scenario as_force = scenario;
    as_force.excitation_quantity = ExcitationQuantity::kForce;
    as_force.amplifier = {};
    as_force.levels = {scenario.levels[static_cast<size_t>(i)]};
    as_force.levels[0].force_amplitude_N = truth.at("steps").at(i).at("force_amplitude_N").get<double>();
    as_force.levels[0].voltage_amplitude_V = 0.0;
    const nlohmann::json& force_n = truth.at("steps").at(i).at("force_N");
    const std::complex<double> ratio = Harmonic(force_n, 2) / Harmonic(force_n, 1);
    as_force.force_distortion = {{.harmonic = 2, .amplitude_ratio = std::abs(ratio), .phase_rad = std::arg(ratio)}};
    std::filesystem::remove_all(force_);
    SimulateInto(as_force, force_);
    const nlohmann::json reference = ReadJsonFile(force_ / "truth.json").at("steps").at(0);
    const nlohmann::json& step = truth.at("steps").at(i);
    for (int k = 1; k <= 3; ++k) {
      const std::complex<double> a = Harmonic(step.at("channels").at("acc3"), k);
      const std::complex<double> b = Harmonic(reference.at("channels").at("acc3"), k);
      EXPECT_LT(std::abs(a - b), 1e-5 * std::abs(Harmonic(reference.at("channels").at("acc3"), 1)))
          << "harmonic " << k;
    }
  }
  // Near f1 the sag costs the response: less force than g0·V0 would give.
  EXPECT_LT(truth.at("steps").at(0).at("force_amplitude_N").get<double>(), 0.71 * kGain_N_per_V * kVoltage_V);
}

TEST(VoltageDrive, AForceDriveWritesNoAmplifier) {
  std::string text = kScenario;
  const std::string from = R"("quantity": "voltage",
                 "amplifier_gain_N_per_V": 10, "amplifier_sag": 0.3,)";
  text.replace(text.find(from), from.size(), "");
  for (size_t at; (at = text.find("\"voltage_amplitude_V\"")) != std::string::npos;)
    text.replace(at, 21, "\"force_amplitude_N\"");
  const Scenario scenario = ParseScenario(text, "force.json");
  EXPECT_FALSE(scenario.VoltageDrive());
  EXPECT_EQ(scenario.levels[0].force_amplitude_N, 0.15);
  EXPECT_EQ(ScenarioToJson(scenario).find("amplifier"), std::string::npos);
}

}  // namespace
}  // namespace beamid::hb
