#include "hb/model_file.h"

#include <string>

#include <fmt/format.h>

#include "hb/errors.h"
#include "hb/input_limits.h"
#include "hb/internal/model_sections.h"
#include "hb/scenario.h"
#include "hb/text_file.h"
#include "hb/version.h"

namespace beamid::hb {
namespace {

constexpr schema::Format kModelFileSchema{kModelFileFormat, "model file",
                                          "give a model file (docs/model-file.md) or a scenario (docs/simulator.md)"};

// A scenario is a model file too (see the header): "format" names either.
enum class ModelFormat { kModel, kScenario };
constexpr schema::Name<ModelFormat> kFormatNames[] = {{ModelFormat::kModel, kModelFileFormat},
                                                      {ModelFormat::kScenario, kScenarioFormat}};

// What a scenario's excitation drives; only a force at a point is a model's.
enum class Drive { kForce, kVoltage, kBaseAcceleration };
constexpr schema::Name<Drive> kDriveNames[] = {
    {Drive::kForce, "force"}, {Drive::kVoltage, "voltage"}, {Drive::kBaseAcceleration, "base_acceleration"}};

}  // namespace

// The declaration of the JSON file (hb/json_schema.h): its writer, reader
// and documentation. The keys of a scenario that a model has no use for are
// read past.
void Describe(auto& io, schema::Like<ModelFile> auto& m) {
  using schema::kOptional;
  using schema::Presence;
  // Checked first, so that another kind of file is named as such instead of
  // by its first missing field.
  ModelFormat format = ModelFormat::kModel;
  io.Choice("format", format, kFormatNames, kOptional);
  std::string version(kVersion);  // the writer's stamp: for the reader of the file, not for beamid
  io.Text("beamid_version", version, schema::TextRule::kAny, kOptional);
  io.Text("name", m.name, schema::TextRule::kAny, kOptional);
  io.Object("beam", m.beam, Presence::kRequired,
            [](auto& b, auto& beam) { internal::DescribeBeam(b, beam, Presence::kRequired); });
  io.Object("support", m, Presence::kRequired, [](auto& s, auto& model) {
    internal::DescribeSupport(s, model.polynomial, model.jenkins, model.one_sided_stiffness_Nm_rad);
  });
  io.Object("attachments", m.attachments, kOptional,
            [](auto& a, auto& attachments) { internal::DescribeAttachments(a, attachments); });
  io.Object("excitation", m.force_position_m, Presence::kRequired, [](auto& e, auto& position_m) {
    Drive drive = Drive::kForce;
    if (schema::Writes(e, false)) e.Choice("quantity", drive, kDriveNames, kOptional);
    // A voltage-driven scenario's shaker still applies a force at position_m.
    e.Check(drive != Drive::kBaseAcceleration,
            "a model file drives the beam with a force at excitation.position_m, not with a base_acceleration "
            "(give a force- or voltage-driven scenario, or a model file)",
            "quantity");
    e.Number("position_m", position_m, "m", schema::Positive());
    for (const char* scenario_only : {"channel", "distortion", "amplifier_gain_N_per_V", "amplifier_sag"})
      e.Ignored(scenario_only);
  });
  io.List("sensors", m.sensors, kMaxPointsOnBeam, kOptional, [](auto& r, auto& sensor) {
    r.Text("channel", sensor.channel, schema::TextRule::kNotEmpty, kOptional);  // absent: x1, x2, …
    r.Number("position_m", sensor.position_m, "m", schema::Positive());
    if (schema::Writes(r, sensor.mass_kg != 0.0))
      r.Number("mass_kg", sensor.mass_kg, "kg", schema::NonNegative(), kOptional);
    // The recording's faults are not the beam's: a model predicts the true motion where the sensor is.
    for (const char* unused : {"quantity", "unit", "gain_error_relative", "delay_s", "stated_position_m"})
      r.Ignored(unused);
  });
  for (const char* scenario_only : {"nominal_beam", "damping", "mesh", "hidden_positions_m", "levels", "timing", "noise"})
    io.Ignored(scenario_only);
}

std::vector<schema::FieldDoc> ModelFileFields() { return schema::Fields<ModelFile>(); }

std::unique_ptr<SupportLaw> ModelFile::MakeSupportLaw() const { return MakePolynomialSupportLaw(polynomial, jenkins, one_sided_stiffness_Nm_rad); }

ModelFile ParseModelFile(const std::string& json_text, const std::string& source) {
  ModelFile model = schema::FromJson<ModelFile>(json_text, source, kModelFileSchema);
  for (std::size_t i = 0; i < model.sensors.size(); ++i) {
    ModelSensor& sensor = model.sensors[i];
    if (sensor.channel.empty()) sensor.channel = "x" + std::to_string(i + 1);
    if (sensor.mass_kg > 0.0) model.attachments.point_masses.push_back({sensor.position_m, sensor.mass_kg});
    sensor.mass_kg = 0.0;
  }
  try {
    model.beam.Validate();
  } catch (const std::invalid_argument& e) {
    throw InputError(source, "", e.what(), "give the beam in SI (m, Pa, kg/m³)");
  }
  const double length = model.beam.length_m;
  auto on_beam = [&](double x, const std::string& what) {
    if (x > length)
      throw InputError(source, "", fmt::format("{} at {} m lies beyond the beam's length {} m", what, x, length),
                       "give a position on the beam, 0 .. beam.length_m");
  };
  on_beam(model.force_position_m, "excitation.position_m");
  for (const auto& s : model.sensors) on_beam(s.position_m, "sensor " + s.channel);
  for (const auto& m : model.attachments.point_masses) on_beam(m.position_m, "a point mass");
  return model;
}

ModelFile ReadModelFile(const std::filesystem::path& file) {
  return ParseModelFile(ReadTextFile(file, "model file", "check the path"), file.string());
}

std::string ModelFileToJson(const ModelFile& model) {
  nlohmann::ordered_json json;
  schema::Writer writer(json);
  Describe(writer, model);
  return json.dump(2) + "\n";
}

void WriteModelFile(const std::filesystem::path& path, const ModelFile& model) {
  WriteTextFileAtomically(path, ModelFileToJson(model));
}

}  // namespace beamid::hb
