#include "hb/backbone_file.h"

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <type_traits>

#include <fmt/format.h>

#include "hb/input_limits.h"
#include "hb/internal/curve_file_json.h"
#include "hb/option_checks.h"
#include "hb/text_file.h"

namespace beamid::hb {
namespace {

using internal::CsvNumber;

constexpr schema::Format kBackboneFileSchema{kBackboneFormat, "backbone file",
                                             "give the PREFIX.json of 'beamid backbone' on a model"};

// A bound on what a file can make the reader hold: `backbone --max-points`
// stays far below it.
constexpr std::size_t kMaxPoints = 1'000'000;

// Every point holds Θ_0..Θ_H and, per sensor, as many displacement phasors.
void CheckShape(const BackboneFile& file, const BackboneFilePoint& p) {
  const std::size_t n = static_cast<std::size_t>(file.harmonics) + 1;
  if (file.harmonics < 1 || p.theta_rad.size() != n)
    throw std::invalid_argument("backbone file: a point holds " + std::to_string(p.theta_rad.size()) +
                                " phasors of theta, not harmonics + 1 = " + std::to_string(n));
  if (p.sensors.size() != file.sensors.size())
    throw std::invalid_argument("backbone file: a point holds " + std::to_string(p.sensors.size()) +
                                " sensors, not the file's " + std::to_string(file.sensors.size()));
  for (const BackboneFileSensorPhasors& s : p.sensors)
    if (s.displacement_m.size() != n)
      throw std::invalid_argument("backbone file: a sensor of a point does not hold harmonics + 1 phasors");
}

// The path of what differs in the first point that names other sensors
// than the file's first point ("points[p].sensors..."), or "".
std::string PointWithOtherSensors(const BackboneFile& f) {
  for (std::size_t j = 1; j < f.points.size(); ++j) {
    const std::string other = internal::OtherSensors(f.points.front().sensors, f.points[j].sensors);
    if (!other.empty()) return fmt::format("points[{}].{}", j, other);
  }
  return {};
}

}  // namespace

// The declaration of the JSON file (hb/json_schema.h): its writer, reader
// and documentation.
void Describe(auto& io, schema::Like<BackboneFile> auto& f) {
  using schema::kOptional;
  using schema::Presence;
  io.Constant("format", kBackboneFormat, kOptional);  // the earlier writer had only "command"
  io.Constant("command", "backbone");
  // A file older than the key reads with version "", not this program's.
  if constexpr (std::remove_reference_t<decltype(io)>::kReading) f.beamid_version.clear();
  io.Text("beamid_version", f.beamid_version, schema::TextRule::kAny, kOptional);
  io.Text("model", f.model);
  io.Text("definition", f.definition);
  io.Integer("harmonics", f.harmonics, 1, option_checks::kMaxHarmonics);
  io.Boolean("complete", f.complete);
  const schema::Count phasors = schema::Count::Exactly(static_cast<std::size_t>(f.harmonics) + 1, "harmonics + 1");
  io.List("points", f.points, kMaxPoints, Presence::kRequired, [&](auto& point_io, auto& p) {
    point_io.Number("theta_amplitude_rad", p.theta_amplitude_rad, "rad", schema::NonNegative());
    point_io.Number("frequency_Hz", p.frequency_hz, "Hz", schema::Positive());
    point_io.Number("force_N", p.force_N, "N");
    point_io.Number("multiple_scales_frequency_Hz", p.multiple_scales_frequency_hz, "Hz",
                    schema::Positive().OrNull());
    point_io.Phasors("theta_rad", p.theta_rad, "rad", phasors);
    point_io.Keyed("sensors", p.sensors, &BackboneFileSensorPhasors::channel, kMaxPointsOnBeam, Presence::kRequired,
                   [&](auto& sensor_io, auto& s) {
                     sensor_io.Number("position_m", s.position_m, "m", schema::Any().OrNull());
                     sensor_io.Phasors("displacement_m", s.displacement_m, "m", phasors);
                   });
  });
  const std::string other = PointWithOtherSensors(f);
  io.Check(other.empty(), "every point names the first point's sensors, in its order, at its positions", other);
}

std::vector<schema::FieldDoc> BackboneFileFields() { return schema::Fields<BackboneFile>(); }

std::string BackboneFileToJson(const BackboneFile& file) {
  // The file repeats the sensors' names and positions in every point.
  BackboneFile written = file;
  for (BackboneFilePoint& p : written.points) {
    CheckShape(written, p);
    for (std::size_t i = 0; i < p.sensors.size(); ++i) {
      p.sensors[i].channel = file.sensors[i].channel;
      p.sensors[i].position_m = file.sensors[i].position_m;
    }
  }
  return schema::ToJson(written);
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
    for (const BackboneFileSensorPhasors& s : p.sensors) {
      const double disp = std::abs(s.displacement_m[1]);
      csv += "," + CsvNumber(disp) + "," + CsvNumber(disp * omega_rad_s * omega_rad_s);
    }
    csv += '\n';
  }
  return csv;
}

BackboneFile BackboneFileFromJson(const std::string& text, const std::string& source) {
  BackboneFile file = schema::FromJson<BackboneFile>(text, source, kBackboneFileSchema);
  if (!file.points.empty())
    for (const BackboneFileSensorPhasors& s : file.points.front().sensors)
      file.sensors.push_back({s.channel, s.position_m});
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
