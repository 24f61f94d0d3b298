#include "hb/model_file.h"

#include <fstream>
#include <sstream>

#include "hb/errors.h"
#include "hb/scenario.h"
#include "hb/strict_json.h"
#include "hb/text_file.h"
#include "hb/version.h"
#include "hb/internal/json_object_reader.h"
#include "hb/internal/json_object_writer.h"

namespace beamid::hb {

using internal::Json;
using internal::ObjectReader;
using internal::OrderedJson;

namespace {

// Checked first, so that another kind of file is named as such instead of by
// its first missing field. A scenario is a model file too (see the header).
void ReadFormat(ObjectReader& top) {
  top.String("beamid_version", "");  // the writer's stamp: for the reader of the file, not for beamid
  const std::string format = top.String("format", std::string(kModelFileFormat));
  if (format != kModelFileFormat && format != kScenarioFormat)
    throw InputError(top.source() + ": field \"format\" is \"" + format + "\", not \"" +
                     std::string(kModelFileFormat) + "\" (or a scenario's \"" + std::string(kScenarioFormat) +
                     "\"). Fix: give a model file (README.md, Model files), or remove \"format\"");
}

}  // namespace

std::unique_ptr<SupportLaw> ModelFile::MakeSupportLaw() const { return MakePolynomialSupportLaw(polynomial, jenkins, one_sided_stiffness_Nm_rad); }

ModelFile ParseModelFile(const std::string& json_text, const std::string& source) {
  constexpr const char* kDoc = "README.md, Model files";
  const Json root = ParseStrictJson<Json>(json_text, source, "see README.md, Model files");
  ModelFile model;
  ObjectReader top(root, source, "", kDoc);
  ReadFormat(top);
  for (const char* scenario_only : {"nominal_beam", "damping", "mesh", "hidden_positions_m", "levels", "timing", "noise"})
    top.Ignore(scenario_only);
  model.name = top.String("name", "beam model");
  {
    ObjectReader beam(top.Raw("beam"), source, "beam", kDoc);
    internal::ReadBeam(beam, model.beam, true);
  }
  internal::ReadSupport(top, kDoc, model.polynomial, model.jenkins, model.one_sided_stiffness_Nm_rad);
  internal::ReadAttachments(top, kDoc, model.attachments);
  {
    ObjectReader e(top.Raw("excitation"), source, "excitation", kDoc);
    e.Ignore("channel");
    e.Ignore("distortion");
    // A voltage-driven scenario's shaker still applies a force at position_m.
    for (const char* drive_only : {"amplifier_gain_N_per_V", "amplifier_sag"}) e.Ignore(drive_only);
    if (e.String("quantity", "force") == "base_acceleration")
      throw std::invalid_argument(source + ": excitation.quantity is base_acceleration: a model file drives the beam "
                                  "with a force at excitation.position_m. Fix: give a force- or voltage-driven "
                                  "scenario, or a model file");
    model.force_position_m = e.Positive("position_m", 0.0);
  }
  if (top.Has("sensors")) {
    const Json& sensors = top.PointList("sensors");
    for (size_t i = 0; i < sensors.size(); ++i) {
      ObjectReader r(sensors[i], source, "sensors[" + std::to_string(i) + "]", kDoc);
      // The recording's faults are not the beam's: a model predicts the true motion where the sensor is.
      for (const char* unused : {"quantity", "unit", "gain_error_relative", "delay_s", "stated_position_m"})
        r.Ignore(unused);
      ModelSensor sensor{r.String("channel", "x" + std::to_string(i + 1)), r.Positive("position_m", 0.0)};
      const double mass = r.NonNegative("mass_kg", 0.0);
      if (mass > 0.0) model.attachments.point_masses.push_back({sensor.position_m, mass});
      model.sensors.push_back(sensor);
    }
  }
  try {
    model.beam.Validate();
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(source + ": " + e.what() + ". Fix: give the beam in SI (m, Pa, kg/m³)");
  }
  const double length = model.beam.length_m;
  auto on_beam = [&](double x, const std::string& what) {
    if (x > length) throw std::invalid_argument(source + ": " + what + " at " + std::to_string(x) +
                                                " m lies beyond the beam's length " + std::to_string(length) + " m");
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
  OrderedJson sensors = OrderedJson::array();
  for (const ModelSensor& sensor : model.sensors) {
    OrderedJson j = OrderedJson::object();
    j["channel"] = sensor.channel;
    j["position_m"] = sensor.position_m;
    sensors.push_back(j);
  }
  OrderedJson root = OrderedJson::object();
  root["format"] = std::string(kModelFileFormat);
  root["beamid_version"] = kVersion;
  root["name"] = model.name;
  root["beam"] = internal::BeamToJson(model.beam);
  root["support"] = internal::SupportToJson(model.polynomial, model.jenkins, model.one_sided_stiffness_Nm_rad);
  root["attachments"] = internal::AttachmentsToJson(model.attachments);
  root["excitation"] = {{"position_m", model.force_position_m}};
  root["sensors"] = sensors;
  return root.dump(2) + "\n";
}

void WriteModelFile(const std::filesystem::path& path, const ModelFile& model) {
  WriteTextFileAtomically(path, ModelFileToJson(model));
}

}  // namespace beamid::hb
