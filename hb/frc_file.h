// The files of `beamid frc` (format "beamid-frc/1"): PREFIX.json and
// PREFIX.csv, the frequency response curves of a model (hb/continuation.h) at
// one or more force levels, and their one reader and writer.
// JSON keys, as earlier files have them: format, command ("frc"),
// beamid_version, model (the model file's name), harmonics (H),
// phasor_convention (a description), first_natural_frequency_Hz, curves
// [{force_N, turning_points, complete, points [{frequency_Hz, stable,
// theta_rad: [[re, im]] for k = 0..H, sensors {<channel>: {position_m,
// displacement_m: [[re, im]] k = 0..H, acceleration_m_s2: [[re, im]] k =
// 0..H}}}]}]. Phasors are peak amplitudes, SI, relative to the force's
// fundamental. The writer adds "format"; a file without it (the earlier
// writer's) reads. JSON has no NaN: a number that is not finite is written as
// null and read back as NaN. Reading throws InputError naming the file, the
// field (e.g. "curves[1].points[3].theta_rad") and the fix.
// CSV columns (FrcFileToCsv): force_N, frequency_Hz, stable (1 or 0), then
// for each harmonic k = 1..H theta_hk_amp_rad, theta_hk_phase_rad, then for
// each sensor and harmonic <channel>_hk_disp_amp_m, _disp_phase_rad,
// _acc_amp_m_s2, _acc_phase_rad; one row per point of every curve.
#pragma once

#include <complex>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "hb/json_schema.h"
#include "hb/version.h"

namespace beamid::hb {

inline constexpr std::string_view kFrcFormat = "beamid-frc/1";
inline constexpr std::string_view kFrcPhasorConvention =
    "x(t) = X0 + sum_k Re(X_k exp(i k w t)), peak amplitudes, SI";

// A sensor of the model: every point holds its phasors, in this order.
struct FrcSensor {
  std::string channel;
  double position_m = 0.0;
};

struct FrcSensorPhasors {
  std::vector<std::complex<double>> displacement_m;     // k = 0..H
  std::vector<std::complex<double>> acceleration_m_s2;  // k = 0..H
  // As the file holds them in every point; the writer takes them from
  // FrcFile::sensors, the reader checks them against the first point's.
  std::string channel;
  double position_m = 0.0;
};

struct FrcPoint {
  double frequency_hz = 0.0;
  bool stable = true;
  std::vector<std::complex<double>> theta_rad;  // Θ_0..Θ_H
  std::vector<FrcSensorPhasors> sensors;        // one per FrcFile::sensors
};

struct FrcCurve {
  double force_N = 0.0;
  int turning_points = 0;
  bool complete = true;
  std::vector<FrcPoint> points;
};

struct FrcFile {
  std::string beamid_version = kVersion;  // "" in files older than the key
  std::string model;                      // the model file's name
  int harmonics = 7;
  std::string phasor_convention = std::string(kFrcPhasorConvention);
  double first_natural_frequency_hz = 0.0;
  // The JSON holds them in every point; a file without points reads with none.
  std::vector<FrcSensor> sensors;
  std::vector<FrcCurve> curves;
};

// The fields of the JSON file: path, type, unit, range (docs/formats.md).
std::vector<schema::FieldDoc> FrcFileFields();

// Throws std::logic_error when a point's sensors do not match `sensors`.
std::string FrcFileToJson(const FrcFile& file);
std::string FrcFileToCsv(const FrcFile& file);
// `source` names the text in messages (the file it came from).
FrcFile FrcFileFromJson(const std::string& text, const std::string& source);

// Atomically (hb/text_file.h): the old file or the new one, never half.
// Both throw InputError when the file cannot be written or read.
void WriteFrcFile(const std::filesystem::path& json_path, const FrcFile& file);
FrcFile ReadFrcFile(const std::filesystem::path& json_path);

}  // namespace beamid::hb
