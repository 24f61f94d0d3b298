// The file of `beamid predict` (format "beamid-prediction/1") and its one
// reader and writer: the identified model's steady state at one position of
// the beam for every step of the fit, with its uncertainty, and, when a
// campaign sensor sits there, the measured phasors beside the predicted ones.
// Keys, as earlier files have them: command ("predict"), beamid_version,
// result (the result.json), model (the model family's name), position_m,
// compared_channel ("" when none), steps [{level, file, frequency_Hz,
// converged, harmonics [{k, displacement_m: [re, im], displacement_std_m:
// [std re, std im], acceleration_m_s2: [re, im], acceleration_amplitude_m_s2,
// and with a compared channel measured_<q>, predicted_<q>: [re, im],
// relative_error}], time_s, acceleration_m_s2, acceleration_std_m_s2}], where
// <q> is the channel's quantity (displacement_m, velocity_m_s or
// acceleration_m_s2). The writer adds "format", "compared_quantity" and
// "campaign_sha256" (the identified campaign's content hash, when the result
// has one); a file without them (an earlier writer's) reads, the quantity
// taken from the keys.
// One declaration of its fields (prediction_io.cc, hb/json_schema.h) drives
// the writer, the reader and the field table of docs/formats.md.
// JSON has no NaN: a number that is not finite is written as null and read
// back as NaN. Reading throws InputError naming the file, the field (e.g.
// "steps[3].harmonics[0].displacement_m") and the fix.
#pragma once

#include <complex>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "hb/json_schema.h"
#include "hb/version.h"
#include "solver/estimation/model_family.h"

namespace beamid::solver {

inline constexpr std::string_view kPredictionFormat = "beamid-prediction/1";

struct PredictionHarmonic {
  int k = 1;
  std::complex<double> displacement_m;
  double displacement_std_real_m = 0.0;
  double displacement_std_imag_m = 0.0;
  std::complex<double> acceleration_m_s2;
  double acceleration_amplitude_m_s2 = 0.0;
  // With a compared channel (for the harmonics it measured), in the
  // channel's own quantity (PredictionFile::compared_quantity).
  bool compared = false;
  std::complex<double> measured;
  std::complex<double> predicted;
  double relative_error = 0.0;  // |predicted - measured| / |measured|
};

struct PredictionStep {
  std::string level;
  std::string file;
  double frequency_hz = 0.0;
  bool converged = true;
  std::vector<PredictionHarmonic> harmonics;  // k = 1..H
  std::vector<double> time_s;                 // one period
  std::vector<double> acceleration_m_s2;      // steady-state history at the position
  std::vector<double> acceleration_std_m_s2;
};

struct PredictionFile {
  std::string beamid_version = kVersion;  // "" in files older than the key
  std::string result_file;                // as given to `beamid predict`
  // The content hash of the campaign the model was identified from (the
  // result's, signal/campaign_hash.h); "" in older files.
  std::string campaign_sha256;
  ModelKind model_kind = ModelKind::kHarmonicBalance;
  double position_m = 0.0;
  std::string compared_channel;   // "" when no campaign sensor sits at position_m
  std::string compared_quantity;  // "displacement_m", "velocity_m_s" or "acceleration_m_s2"; "" without one
  std::vector<PredictionStep> steps;
};

// The fields of the file: path, type, unit, range (docs/formats.md).
std::vector<schema::FieldDoc> PredictionFileFields();

std::string PredictionFileToJson(const PredictionFile& file);
// `source` names the text in messages (the file it came from).
PredictionFile PredictionFileFromJson(const std::string& text, const std::string& source);

// Atomically (hb/text_file.h): the old file or the new one, never half.
// Both throw InputError when the file cannot be written or read.
void WritePredictionFile(const std::filesystem::path& path, const PredictionFile& file);
PredictionFile ReadPredictionFile(const std::filesystem::path& path);

}  // namespace beamid::solver
