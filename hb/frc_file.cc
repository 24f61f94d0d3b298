#include "hb/frc_file.h"

#include <cmath>
#include <stdexcept>

#include <fmt/format.h>
#include "hb/errors.h"
#include "hb/internal/curve_file_json.h"
#include "hb/input_limits.h"
#include "hb/option_checks.h"
#include "hb/text_file.h"

namespace beamid::hb {
namespace {

using internal::CsvNumber;

constexpr schema::Format kFrcFileSchema{kFrcFormat, "frequency response file", "give the PREFIX.json of 'beamid frc'"};

// Bounds on what a file can make the reader hold: `frc --max-points` and
// the force levels of one run stay far below them.
constexpr std::size_t kMaxCurves = 1'000;
constexpr std::size_t kMaxPointsPerCurve = 1'000'000;

// Every point holds Θ_0..Θ_H and one entry per sensor with as many phasors.
void CheckShape(const FrcFile& file, const FrcPoint& p) {
  const std::size_t n = static_cast<std::size_t>(file.harmonics) + 1;
  if (file.harmonics < 0 || p.theta_rad.size() != n)
    throw std::invalid_argument("frc file: a point holds " + std::to_string(p.theta_rad.size()) +
                                " phasors of theta, not harmonics + 1 = " + std::to_string(n));
  if (p.sensors.size() != file.sensors.size())
    throw std::invalid_argument("frc file: a point holds " + std::to_string(p.sensors.size()) +
                                " sensors, not the file's " + std::to_string(file.sensors.size()));
}

// The first point that names other sensors than the file's first point
// (other names, order or positions; NaN, unknown, equals NaN), as the path
// of what differs ("curves[c].points[p].sensors..."), or "".
std::string PointWithOtherSensors(const FrcFile& f) {
  const FrcPoint* first = nullptr;
  for (std::size_t c = 0; c < f.curves.size(); ++c)
    for (std::size_t j = 0; j < f.curves[c].points.size(); ++j) {
      const FrcPoint& p = f.curves[c].points[j];
      if (first == nullptr) first = &p;
      const std::string other = internal::OtherSensors(first->sensors, p.sensors);
      if (!other.empty()) return fmt::format("curves[{}].points[{}].{}", c, j, other);
    }
  return {};
}

}  // namespace

// The declaration of the JSON file (hb/json_schema.h): its writer, reader
// and documentation.
void Describe(auto& io, schema::Like<FrcFile> auto& f) {
  using schema::kOptional;
  using schema::Presence;
  io.Constant("format", kFrcFormat, kOptional);  // the earlier writer had only "command"
  io.Constant("command", "frc");
  io.Text("beamid_version", f.beamid_version, schema::TextRule::kAny, kOptional);
  io.Text("model", f.model);
  io.Integer("harmonics", f.harmonics, 1, option_checks::kMaxHarmonics);
  io.Text("phasor_convention", f.phasor_convention);
  io.Number("first_natural_frequency_Hz", f.first_natural_frequency_hz, "Hz", schema::Positive().OrNull());
  const schema::Count phasors = schema::Count::Exactly(static_cast<std::size_t>(f.harmonics) + 1, "harmonics + 1");
  io.List("curves", f.curves, kMaxCurves, Presence::kRequired, [&](auto& curve_io, auto& curve) {
    curve_io.Number("force_N", curve.force_N, "N");
    curve_io.Integer("turning_points", curve.turning_points, 0, kMaxPointsPerCurve);
    curve_io.Boolean("complete", curve.complete);
    curve_io.List("points", curve.points, kMaxPointsPerCurve, Presence::kRequired, [&](auto& point_io, auto& p) {
      point_io.Number("frequency_Hz", p.frequency_hz, "Hz", schema::Positive().OrNull());
      point_io.Boolean("stable", p.stable);
      point_io.Phasors("theta_rad", p.theta_rad, "rad", phasors);
      point_io.Keyed("sensors", p.sensors, &FrcSensorPhasors::channel, kMaxPointsOnBeam, Presence::kRequired,
                     [&](auto& sensor_io, auto& s) {
                       sensor_io.Number("position_m", s.position_m, "m", schema::Any().OrNull());
                       sensor_io.Phasors("displacement_m", s.displacement_m, "m", phasors);
                       sensor_io.Phasors("acceleration_m_s2", s.acceleration_m_s2, "m/s²", phasors);
                     });
    });
  });
  const std::string other = PointWithOtherSensors(f);
  io.Check(other.empty(), "every point names the first point's sensors, in its order, at its positions", other);
}

std::vector<schema::FieldDoc> FrcFileFields() { return schema::Fields<FrcFile>(); }

std::string FrcFileToJson(const FrcFile& file) {
  // The file repeats the sensors' names and positions in every point.
  FrcFile written = file;
  for (FrcCurve& c : written.curves)
    for (FrcPoint& p : c.points) {
      CheckShape(written, p);
      for (std::size_t i = 0; i < p.sensors.size(); ++i) {
        p.sensors[i].channel = file.sensors[i].channel;
        p.sensors[i].position_m = file.sensors[i].position_m;
      }
    }
  return schema::ToJson(written);
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
  FrcFile file = schema::FromJson<FrcFile>(text, source, kFrcFileSchema);
  for (const FrcCurve& c : file.curves)
    if (!c.points.empty()) {
      for (const FrcSensorPhasors& s : c.points.front().sensors) file.sensors.push_back({s.channel, s.position_m});
      break;
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
