// The scenario file (hb/scenario.h, format "beamid-scenario/1"): a scenario
// whose every field differs from the reader's default reads back from the
// written text field for field, so a field the writer forgets fails here; the
// shipped example scenarios read, write and read again unchanged; a file
// without "format" reads and one with another format is refused; a written
// scenario is also a model file.
#include "hb/scenario.h"

#include <filesystem>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "hb/errors.h"
#include "hb/model_file.h"
#include "hb/version.h"
#include "tests/support/expect_refused.h"
#include "tests/support/schema_checks.h"
#include "tests/support/temp_path.h"

namespace beamid::hb {
namespace {

using beamid::testing::InputErrorOf;
using ::testing::HasSubstr;
using ::testing::Not;

using beamid::testing::TempFile;

// Every field away from the reader's default (and the nominal beam away from
// the true one), so that a field the writer leaves out reads back different.
Scenario Filled() {
  Scenario s;
  s.name = "every field set";
  s.beam = {.length_m = 0.55, .width_m = 0.035, .thickness_m = 0.0045, .youngs_modulus_Pa = 1.95e11,
            .density_kg_m3 = 7810.0, .loss_factor = 0.0031, .rayleigh_mass_1_s = 0.125,
            .rayleigh_stiffness_s = 3.5e-7};
  s.nominal_beam = {.length_m = 0.551, .width_m = 0.036, .thickness_m = 0.0046, .youngs_modulus_Pa = 2.05e11,
                    .density_kg_m3 = 7790.0, .loss_factor = 0.0007};
  s.polynomial = {.k1_Nm_rad = 151.25, .k2_Nm_rad2 = -1234.5, .k3_Nm_rad3 = 3.1e5, .c_Nms_rad = 0.043};
  s.jenkins = JenkinsSupportLaw::Parameters_{.stiffness_Nm_rad = 47.5, .slip_moment_Nm = 0.125};
  s.one_sided_stiffness_Nm_rad = 38.0;
  s.attachments.clamp_rotational_stiffness_Nm_rad = 2.5e4;
  s.attachments.support_translational_stiffness_N_m = 7.25e5;
  s.attachments.point_masses = {{0.41, 0.021}, {0.0, 0.5}};
  s.damping_reference_frequency_hz = 53.5;
  s.modal_damping_ratios = {1.5e-4, 4e-5, 2.5e-4};
  s.mesh_min_elements = 37;
  s.force_channel = "shaker_force";
  s.force_position_m = 0.53;
  s.force_distortion = {{.harmonic = 2, .amplitude_ratio = 0.031, .phase_rad = 0.4},
                        {.harmonic = 3, .amplitude_ratio = 0.007, .phase_rad = -1.2}};
  s.sensors = {{.channel = "vel1", .position_m = 0.1, .quantity = "velocity", .unit = "mm/s", .mass_kg = 0.0},
               {.channel = "acc2", .position_m = 0.3, .quantity = "acceleration", .unit = "g", .mass_kg = 0.0052},
               {.channel = "dsp3", .position_m = 0.53, .quantity = "displacement", .unit = "mm", .mass_kg = 0.011}};
  s.hidden_positions_m = {0.2, 0.45, 0.55};
  // Not a range and not ascending: the writer must keep the run order.
  s.levels = {{.label = "low", .force_amplitude_N = 1.5, .frequencies_hz = {56.0, 55.5, 54.25, 53.1}},
              {.label = "high_2", .force_amplitude_N = 9.75, .frequencies_hz = {50.0, 50.1, 50.3333333333333}}};
  s.timing = {.sample_rate_hz = 6000.0, .max_time_step_s = 2.1e-5, .settle_min_s = 0.35, .settle_max_s = 5.5,
              .settle_tolerance = 2.5e-5, .transient_s = 0.07, .record_s = 0.6, .restart_each_level = false,
              .excitation_stop_fraction = 0.8};
  s.default_noise = {.relative_rms = 0.003, .absolute = 0.005, .adc_bits = 24, .adc_range = 500.0, .pink_rms = 0.0125};
  s.channel_noise["shaker_force"] = {.relative_rms = 0.002, .absolute = 0.0021, .adc_bits = 16, .adc_range = 50.0};
  s.channel_noise["acc2"] = {.relative_rms = 0.0, .absolute = 0.01, .adc_bits = 0, .adc_range = 0.0, .pink_rms = 0.03};
  s.clock_offset_ppm = -12.5;
  s.seed = 987654321012ULL;
  s.amplitude_creep_relative = -0.021;
  return s;
}

// Filled() driven through an amplifier: the levels give voltages.
Scenario FilledVoltage() {
  Scenario s = Filled();
  s.excitation_quantity = ExcitationQuantity::kVoltage;
  s.amplifier = {.gain_N_per_V = 12.5, .sag = 0.35};
  for (ScenarioLevel& level : s.levels) {
    level.voltage_amplitude_V = level.force_amplitude_N / 10.0;
    level.force_amplitude_N = 0.0;
  }
  return s;
}

// Filled() with every measurement artefact: each sensor's gain error, delay
// and stated position, early records of both levels, and the acquisition's
// clock error.
Scenario FilledArtefacts() {
  Scenario s = Filled();
  s.sensors[0].gain_error_relative = 0.05;
  s.sensors[0].delay_s = 1.25e-4;
  s.sensors[1].gain_error_relative = -0.0375;
  s.sensors[2].delay_s = 2e-4;
  s.sensors[2].stated_position_m = 0.54;
  s.sensors[1].stated_position_m = 0.55;  // the beam's end: the test plan may say so
  s.timing.early_records = {{.level = "high_2", .frequency_hz = 50.3333333333333, .settle_s = 0.0125},
                            {.level = "low", .frequency_hz = 54.25, .settle_s = 0.3}};
  s.timing.daq_clock_error_relative = 0.0035;
  return s;
}

void ExpectSameBeam(const BeamProperties& a, const BeamProperties& b) {
  EXPECT_EQ(a.length_m, b.length_m);
  EXPECT_EQ(a.width_m, b.width_m);
  EXPECT_EQ(a.thickness_m, b.thickness_m);
  EXPECT_EQ(a.youngs_modulus_Pa, b.youngs_modulus_Pa);
  EXPECT_EQ(a.density_kg_m3, b.density_kg_m3);
  EXPECT_EQ(a.loss_factor, b.loss_factor);
  EXPECT_EQ(a.rayleigh_mass_1_s, b.rayleigh_mass_1_s);
  EXPECT_EQ(a.rayleigh_stiffness_s, b.rayleigh_stiffness_s);
}

void ExpectSameNoise(const ChannelNoise& a, const ChannelNoise& b) {
  EXPECT_EQ(a.relative_rms, b.relative_rms);
  EXPECT_EQ(a.absolute, b.absolute);
  EXPECT_EQ(a.adc_bits, b.adc_bits);
  EXPECT_EQ(a.adc_range, b.adc_range);
  EXPECT_EQ(a.pink_rms, b.pink_rms);
}

void ExpectSamePhysics(const Scenario& a, const Scenario& b) {
  EXPECT_EQ(a.name, b.name);
  {
    SCOPED_TRACE("beam");
    ExpectSameBeam(a.beam, b.beam);
  }
  {
    SCOPED_TRACE("nominal_beam");
    ExpectSameBeam(a.nominal_beam, b.nominal_beam);
  }
  EXPECT_EQ(a.modal_damping_ratios, b.modal_damping_ratios);
  EXPECT_EQ(a.polynomial.k1_Nm_rad, b.polynomial.k1_Nm_rad);
  EXPECT_EQ(a.polynomial.k2_Nm_rad2, b.polynomial.k2_Nm_rad2);
  EXPECT_EQ(a.polynomial.k3_Nm_rad3, b.polynomial.k3_Nm_rad3);
  EXPECT_EQ(a.polynomial.c_Nms_rad, b.polynomial.c_Nms_rad);
  ASSERT_EQ(a.jenkins.has_value(), b.jenkins.has_value());
  if (a.jenkins) {
    EXPECT_EQ(a.jenkins->stiffness_Nm_rad, b.jenkins->stiffness_Nm_rad);
    EXPECT_EQ(a.jenkins->slip_moment_Nm, b.jenkins->slip_moment_Nm);
  }
  EXPECT_EQ(a.one_sided_stiffness_Nm_rad, b.one_sided_stiffness_Nm_rad);
  EXPECT_EQ(a.attachments.clamp_rotational_stiffness_Nm_rad, b.attachments.clamp_rotational_stiffness_Nm_rad);
  EXPECT_EQ(a.attachments.support_translational_stiffness_N_m, b.attachments.support_translational_stiffness_N_m);
  ASSERT_EQ(a.attachments.point_masses.size(), b.attachments.point_masses.size());
  for (std::size_t i = 0; i < a.attachments.point_masses.size(); ++i) {
    EXPECT_EQ(a.attachments.point_masses[i].position_m, b.attachments.point_masses[i].position_m);
    EXPECT_EQ(a.attachments.point_masses[i].mass_kg, b.attachments.point_masses[i].mass_kg);
  }
  EXPECT_EQ(a.damping_reference_frequency_hz, b.damping_reference_frequency_hz);
  EXPECT_EQ(a.mesh_min_elements, b.mesh_min_elements);
}

void ExpectSame(const Scenario& a, const Scenario& b) {
  ExpectSamePhysics(a, b);
  EXPECT_EQ(a.force_channel, b.force_channel);
  EXPECT_EQ(a.force_position_m, b.force_position_m);
  ASSERT_EQ(a.force_distortion.size(), b.force_distortion.size());
  for (std::size_t i = 0; i < a.force_distortion.size(); ++i) {
    EXPECT_EQ(a.force_distortion[i].harmonic, b.force_distortion[i].harmonic);
    EXPECT_EQ(a.force_distortion[i].amplitude_ratio, b.force_distortion[i].amplitude_ratio);
    EXPECT_EQ(a.force_distortion[i].phase_rad, b.force_distortion[i].phase_rad);
  }
  EXPECT_EQ(a.excitation_quantity, b.excitation_quantity);
  EXPECT_EQ(a.amplifier.gain_N_per_V, b.amplifier.gain_N_per_V);
  EXPECT_EQ(a.amplifier.sag, b.amplifier.sag);
  ASSERT_EQ(a.sensors.size(), b.sensors.size());
  for (std::size_t i = 0; i < a.sensors.size(); ++i) {
    SCOPED_TRACE("sensor " + std::to_string(i));
    EXPECT_EQ(a.sensors[i].channel, b.sensors[i].channel);
    EXPECT_EQ(a.sensors[i].position_m, b.sensors[i].position_m);
    EXPECT_EQ(a.sensors[i].quantity, b.sensors[i].quantity);
    EXPECT_EQ(a.sensors[i].unit, b.sensors[i].unit);
    EXPECT_EQ(a.sensors[i].mass_kg, b.sensors[i].mass_kg);
    EXPECT_EQ(a.sensors[i].gain_error_relative, b.sensors[i].gain_error_relative);
    EXPECT_EQ(a.sensors[i].delay_s, b.sensors[i].delay_s);
    EXPECT_EQ(a.sensors[i].stated_position_m, b.sensors[i].stated_position_m);
  }
  EXPECT_EQ(a.hidden_positions_m, b.hidden_positions_m);
  ASSERT_EQ(a.levels.size(), b.levels.size());
  for (std::size_t i = 0; i < a.levels.size(); ++i) {
    SCOPED_TRACE("level " + std::to_string(i));
    EXPECT_EQ(a.levels[i].label, b.levels[i].label);
    EXPECT_EQ(a.levels[i].force_amplitude_N, b.levels[i].force_amplitude_N);
    EXPECT_EQ(a.levels[i].voltage_amplitude_V, b.levels[i].voltage_amplitude_V);
    EXPECT_EQ(a.levels[i].base_acceleration_amplitude_m_s2, b.levels[i].base_acceleration_amplitude_m_s2);
    EXPECT_EQ(a.levels[i].frequencies_hz, b.levels[i].frequencies_hz);  // exactly, in run order
  }
  EXPECT_EQ(a.timing.sample_rate_hz, b.timing.sample_rate_hz);
  EXPECT_EQ(a.timing.max_time_step_s, b.timing.max_time_step_s);
  EXPECT_EQ(a.timing.settle_min_s, b.timing.settle_min_s);
  EXPECT_EQ(a.timing.settle_max_s, b.timing.settle_max_s);
  EXPECT_EQ(a.timing.settle_tolerance, b.timing.settle_tolerance);
  EXPECT_EQ(a.timing.transient_s, b.timing.transient_s);
  EXPECT_EQ(a.timing.record_s, b.timing.record_s);
  EXPECT_EQ(a.timing.restart_each_level, b.timing.restart_each_level);
  EXPECT_EQ(a.timing.excitation_stop_fraction, b.timing.excitation_stop_fraction);
  EXPECT_EQ(a.timing.daq_clock_error_relative, b.timing.daq_clock_error_relative);
  ASSERT_EQ(a.timing.early_records.size(), b.timing.early_records.size());
  for (std::size_t i = 0; i < a.timing.early_records.size(); ++i) {
    SCOPED_TRACE("early record " + std::to_string(i));
    EXPECT_EQ(a.timing.early_records[i].level, b.timing.early_records[i].level);
    EXPECT_EQ(a.timing.early_records[i].frequency_hz, b.timing.early_records[i].frequency_hz);
    EXPECT_EQ(a.timing.early_records[i].settle_s, b.timing.early_records[i].settle_s);
  }
  {
    SCOPED_TRACE("noise.default");
    ExpectSameNoise(a.default_noise, b.default_noise);
  }
  ASSERT_EQ(a.channel_noise.size(), b.channel_noise.size());
  for (const auto& [channel, noise] : a.channel_noise) {
    SCOPED_TRACE("noise.channels." + channel);
    ASSERT_EQ(b.channel_noise.count(channel), 1u);
    ExpectSameNoise(noise, b.channel_noise.at(channel));
  }
  EXPECT_EQ(a.clock_offset_ppm, b.clock_offset_ppm);
  EXPECT_EQ(a.seed, b.seed);
  EXPECT_EQ(a.amplitude_creep_relative, b.amplitude_creep_relative);
}

TEST(ScenarioFile, EveryFieldSurvivesTheTextAndBackAndTheTextIsStable) {
  const Scenario original = Filled();
  const std::string text = ScenarioToJson(original);
  const Scenario read = ParseScenario(text, "s.json");
  ExpectSame(original, read);
  EXPECT_EQ(ScenarioToJson(read), text);
  EXPECT_THAT(text, HasSubstr("\"format\": \"beamid-scenario/1\""));
  EXPECT_THAT(text, HasSubstr("\"beamid_version\": \"" + std::string(kVersion) + "\""));
}

// The voltage drive's fields (excitation.quantity, the amplifier, each
// level's voltage_amplitude_V instead of its force) survive too.
TEST(ScenarioFile, AVoltageDrivenScenarioSurvivesTheTextAndBack) {
  const Scenario original = FilledVoltage();
  const std::string text = ScenarioToJson(original);
  const Scenario read = ParseScenario(text, "s.json");
  ExpectSame(original, read);
  EXPECT_EQ(ScenarioToJson(read), text);
  EXPECT_THAT(text, HasSubstr("\"quantity\": \"voltage\""));
  EXPECT_THAT(text, Not(HasSubstr("force_amplitude_N")));
}

// The measurement artefacts survive too; a scenario without them writes none
// of their fields (and stays a model file, see below).
TEST(ScenarioFile, TheMeasurementArtefactsSurviveTheTextAndBack) {
  const Scenario original = FilledArtefacts();
  const std::string text = ScenarioToJson(original);
  const Scenario read = ParseScenario(text, "s.json");
  ExpectSame(original, read);
  EXPECT_EQ(ScenarioToJson(read), text);
  EXPECT_EQ(read.sensors[0].StatedPosition_m(), 0.1);  // none stated: the true position
  EXPECT_EQ(read.sensors[2].StatedPosition_m(), 0.54);
  ASSERT_NE(read.EarlyRecordOf("low", 54.25), nullptr);
  EXPECT_EQ(read.EarlyRecordOf("low", 54.25)->settle_s, 0.3);
  EXPECT_EQ(read.EarlyRecordOf("low", 55.5), nullptr);
  EXPECT_EQ(read.EarlyRecordOf("high_2", 54.25), nullptr);
  for (const char* field :
       {"gain_error_relative", "delay_s", "stated_position_m", "early_records", "daq_clock_error_relative"}) {
    EXPECT_THAT(text, HasSubstr(std::string("\"") + field + "\""));
    EXPECT_THAT(ScenarioToJson(Filled()), Not(HasSubstr(field)));
  }
}

// The defaults the reader fills in (no Jenkins element, rigid attachments,
// no distortion, no hidden positions) survive too.
TEST(ScenarioFile, AScenarioWithTheReaderDefaultsSurvivesTheTextAndBack) {
  Scenario s;
  s.sensors = {{.channel = "acc1", .position_m = 0.3}};
  s.levels = {{.label = "only", .force_amplitude_N = 1.0, .frequencies_hz = {54.0}}};
  s.polynomial.k1_Nm_rad = 150.0;
  const Scenario read = ParseScenario(ScenarioToJson(s), "defaults.json");
  ExpectSame(s, read);
  EXPECT_FALSE(read.jenkins.has_value());
  EXPECT_EQ(read.attachments.clamp_rotational_stiffness_Nm_rad, LinearAttachments::kRigid);
  EXPECT_EQ(read.attachments.support_translational_stiffness_N_m, LinearAttachments::kRigid);
}

TEST(ScenarioFile, WrittenFileReadsBack) {
  const TempFile file("scenario.json");
  WriteScenarioFile(file.path, Filled());
  ExpectSame(Filled(), ReadScenario(file.path));
}

// The examples have no "format" (written by hand before the key): they read,
// and what the writer makes of them reads as the same scenario.
TEST(ScenarioFile, EveryShippedExampleReadsWritesAndReadsTheSame) {
  std::vector<std::filesystem::path> examples{"examples/concealed_friction/scenario.json"};
  for (const auto& entry : std::filesystem::directory_iterator("examples/scenarios"))
    if (entry.path().extension() == ".json") examples.push_back(entry.path());
  ASSERT_GE(examples.size(), 7u);
  for (const std::filesystem::path& example : examples) {
    SCOPED_TRACE(example.string());
    const Scenario original = ReadScenario(example);
    const TempFile file("example_scenario.json");
    WriteScenarioFile(file.path, original);
    ExpectSame(original, ReadScenario(file.path));
  }
}

std::string WithFormat(const nlohmann::json& format) {
  nlohmann::json j = nlohmann::json::parse(ScenarioToJson(Filled()));
  j["format"] = format;
  return j.dump();
}

TEST(ScenarioFile, AnotherFormatIsRefusedNamingTheFileTheFieldAndTheFix) {
  const std::string message = InputErrorOf([] { ParseScenario(WithFormat("beamid-model/1"), "runs/s.json"); });
  EXPECT_THAT(message, HasSubstr("runs/s.json: field \"format\" is \"beamid-model/1\", not \"beamid-scenario/1\""));
  EXPECT_THAT(message, HasSubstr("Fix: "));
  EXPECT_THAT(InputErrorOf([] { ParseScenario(WithFormat("beamid-scenario/2"), "s.json"); }),
              HasSubstr("s.json: field \"format\" is \"beamid-scenario/2\""));
  try {
    ParseScenario(WithFormat(1), "s.json");
    ADD_FAILURE() << "accepted a format that is not a string";
  } catch (const std::invalid_argument& e) {
    EXPECT_THAT(e.what(), HasSubstr("s.json: field \"format\" must be a string"));
  }
}

// The declaration (hb/json_schema.h) holds for every field, in each variant
// (force drive with every artefact, voltage drive, base excitation): the
// written text rewrites to the same bytes, and each number out of range,
// required field taken out and unknown key is refused naming its path and
// the fix.
TEST(ScenarioFile, TheDeclarationHoldsForEveryFieldOfEveryVariant) {
  Scenario base = Filled();
  base.excitation_quantity = ExcitationQuantity::kBaseAcceleration;
  base.force_position_m = 0.0;
  for (ScenarioSensor& sensor : base.sensors) sensor.quantity = "acceleration", sensor.unit = "g";
  for (ScenarioLevel& level : base.levels) std::swap(level.base_acceleration_amplitude_m_s2, level.force_amplitude_N);
  for (const Scenario& sample : {FilledArtefacts(), FilledVoltage(), base}) {
    SCOPED_TRACE(ExcitationQuantityName(sample.excitation_quantity));
    beamid::testing::ExpectDeclarationHolds({
        .fields = ScenarioFields(),
        .sample = ScenarioToJson(sample),
        .read = [](const std::string& text) { ParseScenario(text, "x.json"); },
        .rewrite = [](const std::string& text) { return ScenarioToJson(ParseScenario(text, "x.json")); },
    });
  }
}

// Any scenario is a model file (hb/model_file.h): the written one too.
TEST(ScenarioFile, AWrittenScenarioIsAModelFile) {
  const Scenario s = Filled();
  const ModelFile model = ParseModelFile(ScenarioToJson(s), "s.json");
  EXPECT_EQ(model.name, s.name);
  ExpectSameBeam(model.beam, s.beam);
  EXPECT_EQ(model.polynomial.k3_Nm_rad3, s.polynomial.k3_Nm_rad3);
  ASSERT_TRUE(model.jenkins.has_value());
  EXPECT_EQ(model.jenkins->slip_moment_Nm, s.jenkins->slip_moment_Nm);
  EXPECT_EQ(model.one_sided_stiffness_Nm_rad, s.one_sided_stiffness_Nm_rad);
  EXPECT_EQ(model.force_position_m, s.force_position_m);
  ASSERT_EQ(model.sensors.size(), s.sensors.size());
  EXPECT_EQ(model.sensors[2].channel, "dsp3");
  // The concealed masses and the sensors' masses are all the beam carries.
  EXPECT_EQ(model.attachments.point_masses.size(), s.TrueAttachments().point_masses.size());
}

}  // namespace
}  // namespace beamid::hb
