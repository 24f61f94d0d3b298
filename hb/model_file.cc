#include "hb/model_file.h"

#include <fstream>
#include <sstream>

#include "hb/text_file.h"
#include "hb/internal/json_object_reader.h"

namespace beamid::hb {

using internal::Json;
using internal::ObjectReader;

std::unique_ptr<SupportLaw> ModelFile::MakeSupportLaw() const { return MakePolynomialSupportLaw(polynomial, jenkins, one_sided_stiffness_Nm_rad); }

ModelFile ParseModelFile(const std::string& json_text, const std::string& source) {
  Json root;
  try {
    root = Json::parse(json_text);
  } catch (const Json::exception& e) {  // syntax, and numbers beyond double (1e400)
    throw std::invalid_argument(source + ": not valid JSON (" + e.what() + ")");
  }
  constexpr const char* kDoc = "README.md, Model files";
  ModelFile model;
  ObjectReader top(root, source, "", kDoc);
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
    model.force_position_m = e.Positive("position_m", 0.0);
  }
  if (top.Has("sensors")) {
    const Json& sensors = top.Array("sensors");
    for (size_t i = 0; i < sensors.size(); ++i) {
      ObjectReader r(sensors[i], source, "sensors[" + std::to_string(i) + "]", kDoc);
      for (const char* unused : {"quantity", "unit"}) r.Ignore(unused);
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

}  // namespace beamid::hb
