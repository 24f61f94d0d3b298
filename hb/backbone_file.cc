#include "hb/backbone_file.h"

#include <cmath>
#include <numbers>
#include <stdexcept>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "hb/errors.h"
#include "hb/internal/curve_file_json.h"
#include "hb/json_field.h"
#include "hb/option_checks.h"
#include "hb/text_file.h"

namespace beamid::hb {
namespace {

using internal::CsvNumber;
using internal::CurveJson;
using internal::JsonNumber;
using internal::JsonPhasors;
using internal::HarmonicPhasors;
using internal::PhasorsFromJson;
using internal::SamePosition;

constexpr const char* kFix = "give a file written by 'beamid backbone' on a model, or repair that field";
constexpr const char* kFileFix = "give the PREFIX.json of 'beamid backbone' on a model";

// Every point holds Θ_0..Θ_H and, per sensor, as many displacement phasors.
void CheckShape(const BackboneFile& file, const BackboneFilePoint& p) {
  const std::size_t n = static_cast<std::size_t>(file.harmonics) + 1;
  if (file.harmonics < 1 || p.theta_rad.size() != n)
    throw std::invalid_argument("backbone file: a point holds " + std::to_string(p.theta_rad.size()) +
                                " phasors of theta, not harmonics + 1 = " + std::to_string(n));
  if (p.displacement_m.size() != file.sensors.size())
    throw std::invalid_argument("backbone file: a point holds " + std::to_string(p.displacement_m.size()) +
                                " sensors, not the file's " + std::to_string(file.sensors.size()));
  for (const auto& y : p.displacement_m)
    if (y.size() != n)
      throw std::invalid_argument("backbone file: a sensor of a point does not hold harmonics + 1 phasors");
}

BackboneFilePoint PointFromJson(const JsonField& f, BackboneFile& file, bool first) {
  f.OnlyKeys({"theta_amplitude_rad", "frequency_Hz", "force_N", "multiple_scales_frequency_Hz", "theta_rad",
              "sensors"});
  BackboneFilePoint p;
  p.theta_amplitude_rad = f.Number("theta_amplitude_rad");
  p.frequency_hz = f.Number("frequency_Hz");
  p.force_N = f.Number("force_N");
  p.multiple_scales_frequency_hz = f.Number("multiple_scales_frequency_Hz");
  p.theta_rad = HarmonicPhasors(f.At("theta_rad"), file.harmonics);
  const JsonField sensors = f.At("sensors");
  const std::vector<std::string> channels = internal::SensorChannels(sensors);
  if (!first) {
    bool same = channels.size() == file.sensors.size();
    for (std::size_t i = 0; same && i < channels.size(); ++i) same = channels[i] == file.sensors[i].channel;
    if (!same) sensors.Fail("names other sensors than the first point", kFileFix);
  }
  for (std::size_t i = 0; i < channels.size(); ++i) {
    const JsonField s = sensors.At(channels[i]);
    s.OnlyKeys({"position_m", "displacement_m"});
    const double position_m = s.Number("position_m");
    if (first) {
      file.sensors.push_back({channels[i], position_m});
    } else if (!SamePosition(position_m, file.sensors[i].position_m)) {
      s.At("position_m").Fail("differs from the first point's", kFileFix);
    }
    p.displacement_m.push_back(HarmonicPhasors(s.At("displacement_m"), file.harmonics));
  }
  return p;
}

}  // namespace

std::string BackboneFileToJson(const BackboneFile& file) {
  CurveJson points = CurveJson::array();
  for (const BackboneFilePoint& p : file.points) {
    CheckShape(file, p);
    CurveJson sensors = CurveJson::object();
    for (std::size_t i = 0; i < file.sensors.size(); ++i)
      sensors[file.sensors[i].channel] = {{"position_m", JsonNumber(file.sensors[i].position_m)},
                                          {"displacement_m", JsonPhasors(p.displacement_m[i])}};
    points.push_back({{"theta_amplitude_rad", JsonNumber(p.theta_amplitude_rad)},
                      {"frequency_Hz", JsonNumber(p.frequency_hz)},
                      {"force_N", JsonNumber(p.force_N)},
                      {"multiple_scales_frequency_Hz", JsonNumber(p.multiple_scales_frequency_hz)},
                      {"theta_rad", JsonPhasors(p.theta_rad)},
                      {"sensors", sensors}});
  }
  const CurveJson root = {{"format", std::string(kBackboneFormat)},
                          {"command", "backbone"},
                          {"beamid_version", file.beamid_version},
                          {"model", file.model},
                          {"definition", file.definition},
                          {"harmonics", file.harmonics},
                          {"complete", file.complete},
                          {"points", points}};
  return root.dump(1) + "\n";
}

std::string BackboneFileToCsv(const BackboneFile& file) {
  std::string csv = "theta_amp_rad,frequency_Hz,force_N,ms_frequency_Hz";
  for (const BackboneFileSensor& s : file.sensors)
    csv += fmt::format(",{0}_h1_disp_amp_m,{0}_h1_acc_amp_m_s2", s.channel);
  csv += '\n';
  for (const BackboneFilePoint& p : file.points) {
    CheckShape(file, p);
    const double omega_rad_s = 2 * std::numbers::pi * p.frequency_hz;
    csv += CsvNumber(p.theta_amplitude_rad) + "," + CsvNumber(p.frequency_hz) + "," + CsvNumber(p.force_N) + "," +
           (std::isnan(p.multiple_scales_frequency_hz) ? "" : CsvNumber(p.multiple_scales_frequency_hz));
    for (const auto& y : p.displacement_m) {
      const double disp = std::abs(y[1]);
      csv += "," + CsvNumber(disp) + "," + CsvNumber(disp * omega_rad_s * omega_rad_s);
    }
    csv += '\n';
  }
  return csv;
}

BackboneFile BackboneFileFromJson(const std::string& text, const std::string& source) {
  const CurveJson json = ParseJsonObject(text, source, "backbone file", kFileFix);
  const JsonField root(json, "", source, kBackboneFormat, kFix);
  // The earlier writer had no "format", only "command".
  if (root.Has("format")) {
    const std::string format = root.String("format");
    if (format != kBackboneFormat)
      throw InputError(source + ": field \"format\" is \"" + format + "\", not \"" + std::string(kBackboneFormat) +
                       "\". Fix: " + kFileFix);
  }
  const std::string command = root.String("command");
  if (command != "backbone")
    throw InputError(source + ": field \"command\" is \"" + command + "\", not \"backbone\". Fix: " + kFileFix);
  root.OnlyKeys({"format", "command", "beamid_version", "model", "definition", "harmonics", "complete", "points"});
  BackboneFile file;
  file.beamid_version = root.Has("beamid_version") ? root.String("beamid_version") : "";
  file.model = root.String("model");
  file.definition = root.String("definition");
  file.harmonics = root.Integer("harmonics");
  if (file.harmonics < 1 || file.harmonics > option_checks::kMaxHarmonics)
    root.At("harmonics").Fail("must be between 1 and " + std::to_string(option_checks::kMaxHarmonics) + ", not " +
                              std::to_string(file.harmonics));
  file.complete = root.Boolean("complete");
  const JsonField points = root.At("points");
  for (std::size_t i = 0; i < points.Size(); ++i) file.points.push_back(PointFromJson(points.At(i), file, i == 0));
  return file;
}

void WriteBackboneFile(const std::filesystem::path& json_path, const BackboneFile& file) {
  WriteTextFileAtomically(json_path, BackboneFileToJson(file));
}

BackboneFile ReadBackboneFile(const std::filesystem::path& json_path) {
  return BackboneFileFromJson(
      ReadTextFile(json_path, "backbone file", "give the PREFIX.json of 'beamid backbone', or check the path"),
      json_path.string());
}

}  // namespace beamid::hb
