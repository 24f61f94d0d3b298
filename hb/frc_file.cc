#include "hb/frc_file.h"

#include <cmath>
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

constexpr const char* kFix = "give a file written by 'beamid frc', or repair that field";

// Every point holds Θ_0..Θ_H and one entry per sensor with as many phasors.
void CheckShape(const FrcFile& file, const FrcPoint& p) {
  const std::size_t n = static_cast<std::size_t>(file.harmonics) + 1;
  if (file.harmonics < 0 || p.theta_rad.size() != n)
    throw std::invalid_argument("frc file: a point holds " + std::to_string(p.theta_rad.size()) +
                                " phasors of theta, not harmonics + 1 = " + std::to_string(n));
  if (p.sensors.size() != file.sensors.size())
    throw std::invalid_argument("frc file: a point holds " + std::to_string(p.sensors.size()) +
                                " sensors, not the file's " + std::to_string(file.sensors.size()));
  for (const FrcSensorPhasors& s : p.sensors)
    if (s.displacement_m.size() != n || s.acceleration_m_s2.size() != n)
      throw std::invalid_argument("frc file: a sensor of a point does not hold harmonics + 1 phasors");
}

CurveJson PointToJson(const FrcFile& file, const FrcPoint& p) {
  CheckShape(file, p);
  CurveJson sensors = CurveJson::object();
  for (std::size_t i = 0; i < file.sensors.size(); ++i)
    sensors[file.sensors[i].channel] = {{"position_m", JsonNumber(file.sensors[i].position_m)},
                                        {"displacement_m", JsonPhasors(p.sensors[i].displacement_m)},
                                        {"acceleration_m_s2", JsonPhasors(p.sensors[i].acceleration_m_s2)}};
  return {{"frequency_Hz", JsonNumber(p.frequency_hz)},
          {"stable", p.stable},
          {"theta_rad", JsonPhasors(p.theta_rad)},
          {"sensors", sensors}};
}

FrcPoint PointFromJson(const JsonField& f, FrcFile& file, bool first) {
  f.OnlyKeys({"frequency_Hz", "stable", "theta_rad", "sensors"});
  FrcPoint p;
  p.frequency_hz = f.Number("frequency_Hz");
  p.stable = f.Boolean("stable");
  p.theta_rad = HarmonicPhasors(f.At("theta_rad"), file.harmonics);
  const JsonField sensors = f.At("sensors");
  const std::vector<std::string> channels = internal::SensorChannels(sensors);
  if (!first) {
    bool same = channels.size() == file.sensors.size();
    for (std::size_t i = 0; same && i < channels.size(); ++i) same = channels[i] == file.sensors[i].channel;
    if (!same) sensors.Fail("names other sensors than the first point", "give a file written by 'beamid frc'");
  }
  for (std::size_t i = 0; i < channels.size(); ++i) {
    const JsonField s = sensors.At(channels[i]);
    s.OnlyKeys({"position_m", "displacement_m", "acceleration_m_s2"});
    const double position_m = s.Number("position_m");
    if (first) {
      file.sensors.push_back({channels[i], position_m});
    } else if (!SamePosition(position_m, file.sensors[i].position_m)) {
      s.At("position_m").Fail("differs from the first point's", "give a file written by 'beamid frc'");
    }
    p.sensors.push_back({HarmonicPhasors(s.At("displacement_m"), file.harmonics),
                         HarmonicPhasors(s.At("acceleration_m_s2"), file.harmonics)});
  }
  return p;
}

}  // namespace

std::string FrcFileToJson(const FrcFile& file) {
  CurveJson curves = CurveJson::array();
  for (const FrcCurve& c : file.curves) {
    CurveJson points = CurveJson::array();
    for (const FrcPoint& p : c.points) points.push_back(PointToJson(file, p));
    curves.push_back({{"force_N", JsonNumber(c.force_N)},
                      {"turning_points", c.turning_points},
                      {"complete", c.complete},
                      {"points", points}});
  }
  const CurveJson root = {{"format", std::string(kFrcFormat)},
                          {"command", "frc"},
                          {"beamid_version", file.beamid_version},
                          {"model", file.model},
                          {"harmonics", file.harmonics},
                          {"phasor_convention", file.phasor_convention},
                          {"first_natural_frequency_Hz", JsonNumber(file.first_natural_frequency_hz)},
                          {"curves", curves}};
  return root.dump(1) + "\n";
}

std::string FrcFileToCsv(const FrcFile& file) {
  std::string csv = "force_N,frequency_Hz,stable";
  for (int k = 1; k <= file.harmonics; ++k) csv += fmt::format(",theta_h{0}_amp_rad,theta_h{0}_phase_rad", k);
  for (const FrcSensor& s : file.sensors)
    for (int k = 1; k <= file.harmonics; ++k)
      csv += fmt::format(",{0}_h{1}_disp_amp_m,{0}_h{1}_disp_phase_rad,{0}_h{1}_acc_amp_m_s2,{0}_h{1}_acc_phase_rad",
                         s.channel, k);
  csv += '\n';
  for (const FrcCurve& c : file.curves)
    for (const FrcPoint& p : c.points) {
      CheckShape(file, p);
      csv += fmt::format("{},{},{:d}", c.force_N, CsvNumber(p.frequency_hz), p.stable);
      for (int k = 1; k <= file.harmonics; ++k)
        csv += "," + CsvNumber(std::abs(p.theta_rad[k])) + "," + CsvNumber(std::arg(p.theta_rad[k]));
      for (const FrcSensorPhasors& s : p.sensors)
        for (int k = 1; k <= file.harmonics; ++k)
          csv += "," + CsvNumber(std::abs(s.displacement_m[k])) + "," + CsvNumber(std::arg(s.displacement_m[k])) +
                 "," + CsvNumber(std::abs(s.acceleration_m_s2[k])) + "," +
                 CsvNumber(std::arg(s.acceleration_m_s2[k]));
      csv += '\n';
    }
  return csv;
}

FrcFile FrcFileFromJson(const std::string& text, const std::string& source) {
  const CurveJson json =
      ParseJsonObject(text, source, "frequency response file", "give the PREFIX.json of 'beamid frc'");
  const JsonField root(json, "", source, kFrcFormat, kFix);
  // The earlier writer had no "format", only "command".
  if (root.Has("format")) {
    const std::string format = root.String("format");
    if (format != kFrcFormat)
      throw InputError(source + ": field \"format\" is \"" + format + "\", not \"" + std::string(kFrcFormat) +
                       "\". Fix: give the PREFIX.json of 'beamid frc'");
  }
  const std::string command = root.String("command");
  if (command != "frc")
    throw InputError(source + ": field \"command\" is \"" + command +
                     "\", not \"frc\". Fix: give the PREFIX.json of 'beamid frc'");
  root.OnlyKeys({"format", "command", "beamid_version", "model", "harmonics", "phasor_convention",
                 "first_natural_frequency_Hz", "curves"});
  FrcFile file;
  file.beamid_version = root.Has("beamid_version") ? root.String("beamid_version") : "";
  file.model = root.String("model");
  file.harmonics = root.Integer("harmonics");
  if (file.harmonics < 1 || file.harmonics > option_checks::kMaxHarmonics)
    root.At("harmonics").Fail("must be between 1 and " + std::to_string(option_checks::kMaxHarmonics) + ", not " +
                              std::to_string(file.harmonics));
  file.phasor_convention = root.String("phasor_convention");
  file.first_natural_frequency_hz = root.Number("first_natural_frequency_Hz");
  const JsonField curves = root.At("curves");
  bool first = true;
  for (std::size_t i = 0; i < curves.Size(); ++i) {
    const JsonField c = curves.At(i);
    c.OnlyKeys({"force_N", "turning_points", "complete", "points"});
    FrcCurve curve;
    curve.force_N = c.Number("force_N");
    curve.turning_points = c.Integer("turning_points");
    curve.complete = c.Boolean("complete");
    const JsonField points = c.At("points");
    for (std::size_t j = 0; j < points.Size(); ++j) {
      curve.points.push_back(PointFromJson(points.At(j), file, first));
      first = false;
    }
    file.curves.push_back(std::move(curve));
  }
  return file;
}

void WriteFrcFile(const std::filesystem::path& json_path, const FrcFile& file) {
  WriteTextFileAtomically(json_path, FrcFileToJson(file));
}

FrcFile ReadFrcFile(const std::filesystem::path& json_path) {
  return FrcFileFromJson(
      ReadTextFile(json_path, "frequency response file", "give the PREFIX.json of 'beamid frc', or check the path"),
      json_path.string());
}

}  // namespace beamid::hb
