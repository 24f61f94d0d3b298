#include "hb/model_file.h"
#include "hb/scenario.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

namespace beamid::hb {
namespace {

using ::testing::AllOf;
using ::testing::HasSubstr;

const char* kValid = R"({
  "beam": {"length_m": 0.6, "width_m": 0.04, "thickness_m": 0.005, "youngs_modulus_Pa": 2.1e11,
           "density_kg_m3": 7850, "loss_factor": 0.001},
  "support": {"polynomial": {"k1_Nm_rad": 150.43, "k3_Nm_rad3": 4e5, "c_Nms_rad": 0.02},
              "jenkins": {"stiffness_Nm_rad": 50, "slip_moment_Nm": 0.01}},
  "attachments": {"clamp_rotational_stiffness_Nm_rad": 2e4, "point_masses": [{"position_m": 0.3, "mass_kg": 0.01}]},
  "excitation": {"channel": "force", "position_m": 0.57},
  "sensors": [{"channel": "acc1", "position_m": 0.1, "mass_kg": 0.005}, {"channel": "acc3", "position_m": 0.57}],
  "levels": [{"label": "ignored by a model file"}]
})";

std::string Replace(std::string text, const std::string& from, const std::string& to) {
  return text.replace(text.find(from), from.size(), to);
}

void ExpectError(const std::string& text, const std::string& fragment) {
  try {
    ParseModelFile(text, "model.json");
    FAIL() << "accepted a bad model file; expected an error mentioning " << fragment;
  } catch (const std::invalid_argument& e) {
    EXPECT_THAT(e.what(), AllOf(HasSubstr("model.json"), HasSubstr(fragment)));
  }
}

TEST(ModelFile, ReadsEveryFieldInSi) {
  const ModelFile model = ParseModelFile(kValid, "model.json");
  EXPECT_DOUBLE_EQ(model.beam.youngs_modulus_Pa, 2.1e11);
  EXPECT_DOUBLE_EQ(model.beam.loss_factor, 0.001);
  EXPECT_DOUBLE_EQ(model.polynomial.k1_Nm_rad, 150.43);
  EXPECT_DOUBLE_EQ(model.polynomial.k2_Nm_rad2, 0.0);
  ASSERT_TRUE(model.jenkins.has_value());
  EXPECT_DOUBLE_EQ(model.jenkins->slip_moment_Nm, 0.01);
  EXPECT_DOUBLE_EQ(model.attachments.clamp_rotational_stiffness_Nm_rad, 2e4);
  EXPECT_FALSE(std::isfinite(model.attachments.support_translational_stiffness_N_m));
  ASSERT_EQ(model.attachments.point_masses.size(), 2u);  // the given mass and acc1's
  EXPECT_DOUBLE_EQ(model.attachments.point_masses[1].mass_kg, 0.005);
  ASSERT_EQ(model.sensors.size(), 2u);
  EXPECT_EQ(model.sensors[1].channel, "acc3");
  const auto law = model.MakeSupportLaw();
  EXPECT_DOUBLE_EQ(law->InitialStiffness_Nm_rad(), 200.43);  // polynomial + stuck Jenkins
}

TEST(ModelFile, NamesTheFieldAndTheFixInEveryError) {
  ExpectError(Replace(kValid, "\"k3_Nm_rad3\"", "\"k3\""), "field \"support.polynomial.k3\" is not a field here");
  ExpectError(Replace(kValid, "\"k1_Nm_rad\": 150.43", "\"k1_Nm_rad\": -1"), "support.polynomial.k1_Nm_rad");
  ExpectError(Replace(kValid, "\"thickness_m\": 0.005", "\"thickness_m\": \"thin\""), "beam.thickness_m");
  ExpectError(Replace(kValid, "\"position_m\": 0.57}", "\"position_m\": 0.8}"), "beyond the beam");
  ExpectError(Replace(kValid, "\"slip_moment_Nm\": 0.01", "\"slip_moment_Nm\": 0"), "slip_moment_Nm");
  ExpectError("{\"beam\": ", "not valid JSON");
  EXPECT_THROW(ReadModelFile("/nonexistent/model.json"), std::invalid_argument);
}

TEST(ModelFile, AVoltageDrivenScenarioIsAForceAtTheShakerAndABaseExcitedOneIsRefused) {
  const ModelFile model = ParseModelFile(
      Replace(kValid, R"("excitation": {"channel": "force", "position_m": 0.57})",
              R"("excitation": {"channel": "drive", "position_m": 0.57, "quantity": "voltage",
                                "amplifier_gain_N_per_V": 10, "amplifier_sag": 0.3})"),
      "model.json");
  EXPECT_DOUBLE_EQ(model.force_position_m, 0.57);
  ExpectError(Replace(kValid, R"("excitation": {"channel": "force", "position_m": 0.57})",
                      R"("excitation": {"channel": "base", "quantity": "base_acceleration"})"),
              "drives the beam with a force");
}

}  // namespace
}  // namespace beamid::hb

namespace beamid::hb {
namespace {

// A scenario with faults of its recording is still its beam: the model
// predicts the true motion where each sensor truly is.
TEST(ModelFile, AScenarioWithFaultyRecordingsIsItsBeamWithTheSensorsWhereTheyAre) {
  for (const char* file : {"examples/scenarios/paper_sensor_gain.json", "examples/scenarios/paper_sensor_delay.json",
                           "examples/scenarios/paper_sensor_position.json",
                           "examples/scenarios/paper_unsettled_step.json"}) {
    const Scenario scenario = ReadScenario(file);
    const ModelFile model = ReadModelFile(file);
    ASSERT_EQ(model.sensors.size(), scenario.sensors.size()) << file;
    for (std::size_t s = 0; s < model.sensors.size(); ++s)
      EXPECT_EQ(model.sensors[s].position_m, scenario.sensors[s].position_m) << file;
    EXPECT_EQ(model.polynomial.k3_Nm_rad3, scenario.polynomial.k3_Nm_rad3) << file;
  }
}

}  // namespace
}  // namespace beamid::hb
