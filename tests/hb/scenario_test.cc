// Scenario parsing: the examples load, defaults and sweeps are as documented,
// and every user mistake is an std::invalid_argument naming file and field.
#include "hb/scenario.h"

#include <cmath>
#include <filesystem>
#include <string>

#include <gtest/gtest.h>

namespace beamid::hb {
namespace {

const std::string kMinimal = R"({
  "beam": {"length_m": 0.6, "width_m": 0.04, "thickness_m": 0.005, "youngs_modulus_Pa": 2.0e11,
           "density_kg_m3": 7850, "loss_factor": 0.004},
  "nominal_beam": {"youngs_modulus_Pa": 2.1e11},
  "support": {"polynomial": {"k1_Nm_rad": 150, "k3_Nm_rad3": 3e5, "c_Nms_rad": 0.05}},
  "excitation": {"position_m": 0.57},
  "sensors": [{"channel": "acc3", "position_m": 0.57, "unit": "g", "mass_kg": 0.005}],
  "levels": [{"label": "high", "force_amplitude_N": 2, "frequencies_Hz": {"start": 50, "stop": 51, "step": 0.25},
              "direction": "down"}]
})";

// kMinimal with one substring replaced (the mistake under test).
std::string With(const std::string& from, const std::string& to) {
  std::string text = kMinimal;
  const size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return text.replace(at, from.size(), to);
}

void ExpectRejected(const std::string& text, const std::string& expected_in_message) {
  try {
    ParseScenario(text, "my.json");
    ADD_FAILURE() << "accepted a scenario that should fail with: " << expected_in_message;
  } catch (const std::invalid_argument& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("my.json"), std::string::npos) << message;
    EXPECT_NE(message.find(expected_in_message), std::string::npos) << message;
  }
}

TEST(ScenarioTest, ParsesFieldsDefaultsAndDownSweep) {
  const Scenario s = ParseScenario(kMinimal, "my.json");
  EXPECT_EQ(s.beam.youngs_modulus_Pa, 2.0e11);
  EXPECT_EQ(s.nominal_beam.youngs_modulus_Pa, 2.1e11);
  EXPECT_EQ(s.nominal_beam.length_m, 0.6);  // not overridden: the true value
  EXPECT_EQ(s.force_channel, "force");
  EXPECT_EQ(s.sensors[0].quantity, "acceleration");
  ASSERT_EQ(s.levels[0].frequencies_hz.size(), 5u);
  EXPECT_DOUBLE_EQ(s.levels[0].frequencies_hz.front(), 51.0);  // run downwards
  EXPECT_DOUBLE_EQ(s.levels[0].frequencies_hz.back(), 50.0);
  EXPECT_FALSE(s.jenkins.has_value());
  EXPECT_FALSE(std::isfinite(s.attachments.clamp_rotational_stiffness_Nm_rad));
  // The sensor's mass is physics: a point mass of the true beam.
  ASSERT_EQ(s.TrueAttachments().point_masses.size(), 1u);
  EXPECT_EQ(s.TrueAttachments().point_masses[0].mass_kg, 0.005);
  EXPECT_EQ(s.MakeSupportLaw()->Name(), "polynomial");
}

TEST(ScenarioTest, JenkinsIsAddedInParallel) {
  const Scenario s = ParseScenario(
      With(R"("c_Nms_rad": 0.05}})", R"("c_Nms_rad": 0.05}, "jenkins": {"stiffness_Nm_rad": 50, "slip_moment_Nm": 0.1}})"),
      "my.json");
  const auto law = s.MakeSupportLaw();
  EXPECT_EQ(law->NumInternalStates(), 1);
  EXPECT_DOUBLE_EQ(law->InitialStiffness_Nm_rad(), 200.0);
}

TEST(ScenarioTest, RejectsMistakesWithFileAndField) {
  ExpectRejected("{", "not valid JSON");
  ExpectRejected(With("\"youngs_modulus_Pa\": 2.0e11", "\"youngs_modulus_Pa\": 1e400"), "not valid JSON");  // fuzz finding
  ExpectRejected(With("\"loss_factor\"", "\"loss_factr\""), "field \"beam.loss_factr\" is not a field here");
  ExpectRejected(With("\"unit\": \"g\"", "\"unit\": \"mm\""), "sensors[0].unit");
  ExpectRejected(With("\"position_m\": 0.57}", "\"position_m\": 0.7}"), "excitation.position_m");
  ExpectRejected(With("\"label\": \"high\"", "\"label\": \"a/b\""), "levels[0].label");
  ExpectRejected(With("\"direction\": \"down\"", "\"direction\": \"sideways\""), "direction");
  ExpectRejected(With("\"k1_Nm_rad\": 150, ", ""), "field \"support.polynomial.k1_Nm_rad\" is missing");
  ExpectRejected(With("\"width_m\": 0.04, ", ""), "field \"beam.width_m\" is missing");
  ExpectRejected(With("\"channel\": \"acc3\"", "\"channel\": \"force\""), "used twice");
  ExpectRejected(With("\"start\": 50, \"stop\": 51", "\"start\": 50, \"stop\": 600"), "Nyquist");
  ExpectRejected(With("\"force_amplitude_N\": 2", "\"force_amplitude_N\": -2"), "field \"levels[0].force_amplitude_N\" = -2 lies outside > 0");
}

// Sizes that would exhaust memory or run without bound are refused with the
// field named, before any simulation (they ended as bad_alloc or an endless run).
TEST(ScenarioTest, RejectsTimingBeyondItsLimits) {
  const std::string levels = R"("direction": "down"}])";
  ExpectRejected(With(levels, levels + R"(, "timing": {"record_s": 1e6})"), "timing.record_s");
  ExpectRejected(With(levels, levels + R"(, "timing": {"max_time_step_s": 1e-12})"), "timing.max_time_step_s");
  ExpectRejected(With(levels, levels + R"(, "timing": {"settle_max_s": 1e5})"), "timing.settle_max_s");
}

// The rig's quirks (docs/simulator.md): each refused outside its range, with
// the field and the fix named.
TEST(ScenarioTest, RejectsRigQuirksOutsideTheirRanges) {
  const std::string levels = R"("direction": "down"}])";
  const std::string timing = R"("timing": {"transient_s": 0.05, "record_s": 0.45, "excitation_stop_fraction": )";
  ExpectRejected(With(levels, levels + ", " + timing + "0.05}"), "timing.excitation_stop_fraction\" breaks the rule: excitation_stop_fraction is 0 (never)");
  ExpectRejected(With(levels, levels + ", " + timing + "1.0}"), "inside the steady record");
  EXPECT_EQ(ParseScenario(With(levels, levels + ", " + timing + "0.8}"), "my.json").timing.excitation_stop_fraction, 0.8);

  // The creep's scale must stay positive over transient and record.
  ExpectRejected(With(levels, levels + R"(, "noise": {"amplitude_creep_relative": 2.0})"),
                 "noise.amplitude_creep_relative\" breaks the rule");
  EXPECT_EQ(ParseScenario(With(levels, levels + R"(, "noise": {"amplitude_creep_relative": -0.02})"), "my.json")
                .amplitude_creep_relative,
            -0.02);
  ExpectRejected(With(levels, levels + R"(, "noise": {"default": {"pink_rms": -1}})"),
                 "noise.default.pink_rms\" = -1 lies outside ≥ 0");

  const std::string excitation = R"("excitation": {"position_m": 0.57})";
  const std::string voltage = R"("excitation": {"position_m": 0.57, "quantity": "voltage", "amplifier_gain_N_per_V": 8)";
  const std::string volts = R"("voltage_amplitude_V": 0.25)";
  ExpectRejected(With(excitation, voltage + "}"), "levels[0].force_amplitude_N\" is not the drive");
  ExpectRejected(With(excitation, R"("excitation": {"position_m": 0.57, "quantity": "voltage"})"),
                 "excitation.amplifier_gain_N_per_V\" is missing");
  ExpectRejected(With(excitation, R"("excitation": {"position_m": 0.57, "quantity": "current"})"),
                 "excitation.quantity\" is \"current\", not one of \"force\", \"voltage\", \"base_acceleration\"");
  ExpectRejected(With(excitation, R"("excitation": {"position_m": 0.57, "amplifier_sag": 0.2})"),
                 "excitation.amplifier_sag\" belongs to a voltage drive");
  const std::string voltage_levels = With("\"force_amplitude_N\": 2", volts);
  ExpectRejected(voltage_levels, "levels[0].voltage_amplitude_V\" is not the drive with excitation.quantity \"force\"");
  auto with_voltage = [&](const std::string& amplifier_end) {
    std::string text = voltage_levels;
    return text.replace(text.find(excitation), excitation.size(), voltage + amplifier_end);
  };
  ExpectRejected(with_voltage(R"(, "amplifier_sag": 1.0})"), "excitation.amplifier_sag\" breaks the rule: amplifier_sag < 1");
  const Scenario s = ParseScenario(with_voltage(R"(, "amplifier_sag": 0.3})"), "my.json");
  EXPECT_TRUE(s.VoltageDrive());
  EXPECT_EQ(s.amplifier.gain_N_per_V, 8.0);
  EXPECT_EQ(s.levels[0].voltage_amplitude_V, 0.25);
  EXPECT_EQ(s.levels[0].force_amplitude_N, 0.0);
  // g(f) = g0·(1 − sag/(1 + ((f − f1)/b)²)), b = 2 % of f1.
  EXPECT_DOUBLE_EQ(s.amplifier.Gain_N_per_V(50.0, 50.0), 8.0 * 0.7);
  EXPECT_DOUBLE_EQ(s.amplifier.Gain_N_per_V(51.0, 50.0), 8.0 * (1.0 - 0.3 / 2.0));
}

// The measurement artefacts (docs/simulator.md): each refused outside its
// range naming the field; the early record's step must exist.
TEST(ScenarioTest, RejectsMeasurementArtefactsOutsideTheirRanges) {
  const std::string sensor = R"("mass_kg": 0.005)";
  ExpectRejected(With(sensor, sensor + R"(, "gain_error_relative": -1)"), "sensors[0].gain_error_relative\" = -1 lies outside > -1");
  ExpectRejected(With(sensor, sensor + R"(, "gain_error_relative": "5 %")"), "sensors[0].gain_error_relative\" must be a number, not a string");
  ExpectRejected(With(sensor, sensor + R"(, "delay_s": -1e-4)"), "sensors[0].delay_s\" = -0.0001 lies outside 0 .. 0.01");
  ExpectRejected(With(sensor, sensor + R"(, "delay_s": 0.05)"), "sensors[0].delay_s\" = 0.05 lies outside 0 .. 0.01");
  ExpectRejected(With(sensor, sensor + R"(, "stated_position_m": 0.61)"), "sensors[0].stated_position_m = 0.61");
  ExpectRejected(With(sensor, sensor + R"(, "stated_position_m": 0)"), "sensors[0].stated_position_m\" = 0 lies outside > 0");
  ExpectRejected(With(sensor, sensor + R"(, "stated_position": 0.5)"), "field \"sensors[0].stated_position\" is not a field here");
  const Scenario s = ParseScenario(
      With(sensor, sensor + R"(, "gain_error_relative": -0.02, "delay_s": 2e-4, "stated_position_m": 0.6)"), "my.json");
  EXPECT_EQ(s.sensors[0].gain_error_relative, -0.02);
  EXPECT_EQ(s.sensors[0].delay_s, 2e-4);
  EXPECT_EQ(s.sensors[0].StatedPosition_m(), 0.6);
  EXPECT_EQ(s.sensors[0].position_m, 0.57);

  // The level runs 51, 50.75, 50.5, 50.25, 50 Hz.
  const std::string levels = R"("direction": "down"}])";
  auto with_clock = [&](const std::string& value) {
    return With(levels, levels + R"(, "timing": {"daq_clock_error_relative": )" + value + "}");
  };
  ExpectRejected(with_clock("0.06"), "timing.daq_clock_error_relative\" = 0.06 lies outside -0.05 .. 0.05");
  ExpectRejected(with_clock("-0.051"), "timing.daq_clock_error_relative\" = -0.051 lies outside -0.05 .. 0.05");
  ExpectRejected(with_clock(R"("0.2 %")"), "timing.daq_clock_error_relative\" must be a number, not a string");
  EXPECT_EQ(ParseScenario(with_clock("-0.003"), "my.json").timing.daq_clock_error_relative, -0.003);
  EXPECT_EQ(ParseScenario(with_clock("0.05"), "my.json").timing.daq_clock_error_relative, 0.05);
  EXPECT_EQ(ParseScenario(kMinimal, "my.json").timing.daq_clock_error_relative, 0.0);
  auto with_early = [&](const std::string& entry) {
    return With(levels, levels + R"(, "timing": {"early_records": [)" + entry + "]}");
  };
  ExpectRejected(with_early(R"({"level": "low", "frequency_Hz": 50.5, "settle_s": 0.1})"),
                 "timing.early_records[0].level\" breaks the rule: 'low' is not a level of the scenario; give one of: high");
  ExpectRejected(with_early(R"({"frequency_Hz": 50.5, "settle_s": 0.1})"), "timing.early_records[0].level\" is missing");
  ExpectRejected(with_early(R"({"level": "high", "frequency_Hz": 50.6, "settle_s": 0.1})"),
                 "timing.early_records[0].frequency_Hz\" breaks the rule: 50.6 Hz is not a step");
  ExpectRejected(with_early(R"({"level": "high", "frequency_Hz": 50.5000001, "settle_s": 0.1})"),
                 "is not a step of level 'high'");
  ExpectRejected(with_early(R"({"level": "high", "settle_s": 0.1})"), "timing.early_records[0].frequency_Hz\" is missing");
  ExpectRejected(with_early(R"({"level": "high", "frequency_Hz": 50.5, "settle_s": 0})"),
                 "timing.early_records[0].settle_s\" = 0 lies outside > 0 .. 3600");
  ExpectRejected(with_early(R"({"level": "high", "frequency_Hz": 50.5, "settle_s": 0.1, "record_s": 1})"),
                 "timing.early_records[0].record_s\" is not a field here");
  ExpectRejected(with_early(R"({"level": "high", "frequency_Hz": 50.5, "settle_s": 0.1},
                               {"level": "high", "frequency_Hz": 50.5, "settle_s": 0.2})"),
                 "timing.early_records[1].frequency_Hz\" breaks the rule: names the step of timing.early_records[0] again");
  ExpectRejected(With(R"("frequencies_Hz": {"start": 50, "stop": 51, "step": 0.25},
              "direction": "down"}])",
                      R"("frequencies_Hz": [50, 51, 50]}], "timing": {"early_records": [)"
                      R"({"level": "high", "frequency_Hz": 50, "settle_s": 0.1}]})"),
                 "is run 2 times by level 'high'");
  // Within 1e-9 relative, as a writer may round the last digits.
  const Scenario early = ParseScenario(with_early(R"({"level": "high", "frequency_Hz": 50.50000000001, "settle_s": 0.1})"), "my.json");
  ASSERT_EQ(early.timing.early_records.size(), 1u);
  EXPECT_NE(early.EarlyRecordOf("high", 50.5), nullptr);
  EXPECT_EQ(early.EarlyRecordOf("high", 50.75), nullptr);
}

TEST(ScenarioTest, EveryExampleScenarioLoads) {
  int count = 0;
  for (const auto& entry : std::filesystem::directory_iterator("examples/scenarios")) {
    if (entry.path().extension() != ".json") continue;
    SCOPED_TRACE(entry.path().string());
    const Scenario s = ReadScenario(entry.path());
    EXPECT_EQ(s.levels.size(), 3u);
    EXPECT_EQ(s.sensors.size(), 3u);
    ++count;
  }
  EXPECT_GE(count, 6);
}

}  // namespace
}  // namespace beamid::hb
