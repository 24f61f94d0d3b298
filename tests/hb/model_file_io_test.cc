// The model file (hb/model_file.h, format "beamid-model/1"): a model whose
// every field differs from the reader's default reads back from the written
// text field for field, so a field the writer forgets fails here; the shipped
// example model reads, writes and reads again unchanged; a file without
// "format" and a scenario's format read, any other format is refused.
#include "hb/model_file.h"

#include <filesystem>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "hb/errors.h"
#include "hb/version.h"
#include "tests/support/expect_refused.h"
#include "tests/support/schema_checks.h"
#include "tests/support/temp_path.h"

namespace beamid::hb {
namespace {

using beamid::testing::InputErrorOf;
using ::testing::HasSubstr;

using beamid::testing::TempFile;

// Every field away from the reader's default, so that a field the writer
// leaves out reads back different.
ModelFile Filled() {
  ModelFile m;
  m.name = "every field set";
  m.beam = {.length_m = 0.55, .width_m = 0.035, .thickness_m = 0.0045, .youngs_modulus_Pa = 1.95e11,
            .density_kg_m3 = 7810.0, .loss_factor = 0.0031};
  m.polynomial = {.k1_Nm_rad = 151.25, .k2_Nm_rad2 = -1234.5, .k3_Nm_rad3 = 3.1e5, .c_Nms_rad = 0.043};
  m.jenkins = JenkinsSupportLaw::Parameters_{.stiffness_Nm_rad = 47.5, .slip_moment_Nm = 0.125};
  m.one_sided_stiffness_Nm_rad = -20.0;  // a softer positive side: negative is allowed while k1 + k_a ≥ 0
  m.attachments.clamp_rotational_stiffness_Nm_rad = 2.5e4;
  m.attachments.support_translational_stiffness_N_m = 7.25e5;
  m.attachments.point_masses = {{0.41, 0.021}, {0.1, 0.0052}};
  m.force_position_m = 0.53;
  // Not the reader's default names (x1, x2).
  m.sensors = {{.channel = "acc1", .position_m = 0.1}, {.channel = "acc3", .position_m = 0.53}};
  return m;
}

void ExpectSame(const ModelFile& a, const ModelFile& b) {
  EXPECT_EQ(a.name, b.name);
  EXPECT_EQ(a.beam.length_m, b.beam.length_m);
  EXPECT_EQ(a.beam.width_m, b.beam.width_m);
  EXPECT_EQ(a.beam.thickness_m, b.beam.thickness_m);
  EXPECT_EQ(a.beam.youngs_modulus_Pa, b.beam.youngs_modulus_Pa);
  EXPECT_EQ(a.beam.density_kg_m3, b.beam.density_kg_m3);
  EXPECT_EQ(a.beam.loss_factor, b.beam.loss_factor);
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
    SCOPED_TRACE("point mass " + std::to_string(i));
    EXPECT_EQ(a.attachments.point_masses[i].position_m, b.attachments.point_masses[i].position_m);
    EXPECT_EQ(a.attachments.point_masses[i].mass_kg, b.attachments.point_masses[i].mass_kg);
  }
  EXPECT_EQ(a.force_position_m, b.force_position_m);
  ASSERT_EQ(a.sensors.size(), b.sensors.size());
  for (std::size_t i = 0; i < a.sensors.size(); ++i) {
    SCOPED_TRACE("sensor " + std::to_string(i));
    EXPECT_EQ(a.sensors[i].channel, b.sensors[i].channel);
    EXPECT_EQ(a.sensors[i].position_m, b.sensors[i].position_m);
  }
}

TEST(ModelFileIo, EveryFieldSurvivesTheTextAndBackAndTheTextIsStable) {
  const ModelFile original = Filled();
  const std::string text = ModelFileToJson(original);
  const ModelFile read = ParseModelFile(text, "m.json");
  ExpectSame(original, read);
  EXPECT_EQ(ModelFileToJson(read), text);
  EXPECT_THAT(text, HasSubstr("\"format\": \"beamid-model/1\""));
  EXPECT_THAT(text, HasSubstr("\"beamid_version\": \"" + std::string(kVersion) + "\""));
  // The sensors' masses are already point masses: written once, not twice.
  std::size_t masses = 0;
  for (std::size_t at = text.find("\"mass_kg\""); at != std::string::npos; at = text.find("\"mass_kg\"", at + 1))
    ++masses;
  EXPECT_EQ(masses, original.attachments.point_masses.size());
}

// The defaults the reader fills in (no Jenkins element, rigid attachments,
// no point masses, no sensors) survive too.
TEST(ModelFileIo, AModelWithTheReaderDefaultsSurvivesTheTextAndBack) {
  ModelFile m;
  m.polynomial.k1_Nm_rad = 150.0;
  const ModelFile read = ParseModelFile(ModelFileToJson(m), "defaults.json");
  ExpectSame(m, read);
  EXPECT_FALSE(read.jenkins.has_value());
  EXPECT_EQ(read.attachments.clamp_rotational_stiffness_Nm_rad, LinearAttachments::kRigid);
  EXPECT_EQ(read.attachments.support_translational_stiffness_N_m, LinearAttachments::kRigid);
}

TEST(ModelFileIo, WrittenFileReadsBack) {
  const TempFile file("model.json");
  WriteModelFile(file.path, Filled());
  ExpectSame(Filled(), ReadModelFile(file.path));
}

// The example has no "format" (written by hand before the key): it reads,
// and what the writer makes of it reads as the same model.
TEST(ModelFileIo, TheShippedExampleReadsWritesAndReadsTheSame) {
  const ModelFile original = ReadModelFile("examples/paper_setup/model.json");
  EXPECT_EQ(original.sensors.size(), 3u);
  const TempFile file("example_model.json");
  WriteModelFile(file.path, original);
  ExpectSame(original, ReadModelFile(file.path));
}

std::string WithFormat(const nlohmann::json& format) {
  nlohmann::json j = nlohmann::json::parse(ModelFileToJson(Filled()));
  j["format"] = format;
  return j.dump();
}

TEST(ModelFileIo, AScenariosFormatReadsAndAnyOtherIsRefusedNamingTheFileTheFieldAndTheFix) {
  ExpectSame(Filled(), ParseModelFile(WithFormat("beamid-scenario/1"), "m.json"));
  const std::string message = InputErrorOf([] { ParseModelFile(WithFormat("beamid-result/1"), "runs/m.json"); });
  EXPECT_THAT(message, HasSubstr("runs/m.json: field \"format\" is \"beamid-result/1\", not one of \"beamid-model/1\", \"beamid-scenario/1\""));
  EXPECT_THAT(message, HasSubstr("Fix: "));
  try {
    ParseModelFile(WithFormat(nlohmann::json::array()), "m.json");
    ADD_FAILURE() << "accepted a format that is not a string";
  } catch (const std::invalid_argument& e) {
    EXPECT_THAT(e.what(), HasSubstr("m.json: field \"format\" must be a string"));
  }
}

// The declaration (hb/json_schema.h) holds for every field: the written text
// rewrites to the same bytes, and each number out of range, required field
// taken out and unknown key is refused naming its path and the fix.
TEST(ModelFileIo, TheDeclarationHoldsForEveryField) {
  beamid::testing::ExpectDeclarationHolds({
      .fields = ModelFileFields(),
      .sample = ModelFileToJson(Filled()),
      .read = [](const std::string& text) { ParseModelFile(text, "x.json"); },
      .rewrite = [](const std::string& text) { return ModelFileToJson(ParseModelFile(text, "x.json")); },
  });
}

}  // namespace
}  // namespace beamid::hb
