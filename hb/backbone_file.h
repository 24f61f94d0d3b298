// The files of `beamid backbone` on a model (format "beamid-backbone/1"):
// PREFIX.json and PREFIX.csv, the model's backbone by phase resonance
// (hb/backbone.h) with the corrected multiple-scales backbone beside it, and
// their one reader and writer, driven by one declaration (hb/json_schema.h).
// (The measured backbone of `backbone --measured` is another format:
// solver/backbone/measured_backbone_io.h.)
// JSON keys, as earlier files have them: format, command ("backbone"),
// beamid_version, model (the model file's name), definition (a description),
// harmonics (H), complete, points [{theta_amplitude_rad, frequency_Hz,
// force_N, multiple_scales_frequency_Hz (null when there is none), theta_rad:
// [[re, im]] for k = 0..H, sensors {<channel>: {position_m, displacement_m:
// [[re, im]] k = 0..H}}}]. Phasors are peak amplitudes, SI. The writer adds
// "format"; a file without it (the earlier writer's) reads. JSON has no NaN: a
// number that is not finite is written as null and read back as NaN. Reading
// throws InputError naming the file, the field (e.g. "points[3].force_N") and
// the fix.
// CSV columns (BackboneFileToCsv): theta_amp_rad, frequency_Hz, force_N,
// ms_frequency_Hz (empty when there is none), then for each sensor
// <channel>_h1_disp_amp_m, <channel>_h1_acc_amp_m_s2 (the first harmonic's
// displacement amplitude times (2π frequency)²).
#pragma once

#include <complex>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "hb/json_schema.h"
#include "hb/version.h"

namespace beamid::hb {

inline constexpr std::string_view kBackboneFormat = "beamid-backbone/1";
inline constexpr std::string_view kBackboneDefinition =
    "phase resonance: first harmonic of theta in quadrature with the force";

// A sensor of the model: every point holds its phasors, in this order.
struct BackboneFileSensor {
  std::string channel;
  double position_m = 0.0;
};

struct BackboneFileSensorPhasors {
  std::vector<std::complex<double>> displacement_m;  // k = 0..H
  // As the file holds them in every point; the writer takes them from
  // BackboneFile::sensors, the reader checks them against the first point's.
  std::string channel;
  double position_m = 0.0;
};

struct BackboneFilePoint {
  double theta_amplitude_rad = 0.0;
  double frequency_hz = 0.0;
  double force_N = 0.0;  // signed (hb/backbone.h)
  double multiple_scales_frequency_hz = 0.0;  // NaN when there is none (null in the JSON, empty in the CSV)
  std::vector<std::complex<double>> theta_rad;     // Θ_0..Θ_H
  std::vector<BackboneFileSensorPhasors> sensors;  // one per BackboneFile::sensors
};

struct BackboneFile {
  std::string beamid_version = kVersion;  // "" in files older than the key
  std::string model;                      // the model file's name
  std::string definition = std::string(kBackboneDefinition);
  int harmonics = 7;
  bool complete = true;
  // The JSON holds them in every point; a file without points reads with none.
  std::vector<BackboneFileSensor> sensors;
  std::vector<BackboneFilePoint> points;
};

// The fields of the JSON file: path, type, unit, range (docs/formats.md).
std::vector<schema::FieldDoc> BackboneFileFields();

// Throws std::invalid_argument when a point's sensors do not match `sensors`.
std::string BackboneFileToJson(const BackboneFile& file);
std::string BackboneFileToCsv(const BackboneFile& file);
// `source` names the text in messages (the file it came from).
BackboneFile BackboneFileFromJson(const std::string& text, const std::string& source);

// Atomically (hb/text_file.h): the old file or the new one, never half.
// Both throw InputError when the file cannot be written or read.
void WriteBackboneFile(const std::filesystem::path& json_path, const BackboneFile& file);
BackboneFile ReadBackboneFile(const std::filesystem::path& json_path);

}  // namespace beamid::hb
