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
  ExpectRejected(With("\"loss_factor\"", "\"loss_factr\""), "unknown field 'loss_factr'");
  ExpectRejected(With("\"unit\": \"g\"", "\"unit\": \"mm\""), "sensors[0].unit");
  ExpectRejected(With("\"position_m\": 0.57}", "\"position_m\": 0.7}"), "excitation.position_m");
  ExpectRejected(With("\"label\": \"high\"", "\"label\": \"a/b\""), "levels[0].label");
  ExpectRejected(With("\"direction\": \"down\"", "\"direction\": \"sideways\""), "direction");
  ExpectRejected(With("\"k1_Nm_rad\": 150, ", ""), "needs the field 'k1_Nm_rad'");
  ExpectRejected(With("\"width_m\": 0.04, ", ""), "beam.width_m is required");
  ExpectRejected(With("\"channel\": \"acc3\"", "\"channel\": \"force\""), "used twice");
  ExpectRejected(With("\"start\": 50, \"stop\": 51", "\"start\": 50, \"stop\": 600"), "Nyquist");
  ExpectRejected(With("\"force_amplitude_N\": 2", "\"force_amplitude_N\": -2"), "force_amplitude_N must be positive");
}

// Sizes that would exhaust memory or run without bound are refused with the
// field named, before any simulation (they ended as bad_alloc or an endless run).
TEST(ScenarioTest, RejectsTimingBeyondItsLimits) {
  const std::string levels = R"("direction": "down"}])";
  ExpectRejected(With(levels, levels + R"(, "timing": {"record_s": 1e6})"), "timing.record_s");
  ExpectRejected(With(levels, levels + R"(, "timing": {"max_time_step_s": 1e-12})"), "timing.max_time_step_s");
  ExpectRejected(With(levels, levels + R"(, "timing": {"settle_max_s": 1e5})"), "timing.settle_max_s");
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
