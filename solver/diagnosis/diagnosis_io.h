// diagnosis.json, the file of `beamid diagnose` (format "beamid-diagnosis/1"),
// and its one reader and writer: a DiagnosisResult (solver/diagnosis/
// diagnosis.h) with its misfit location and the support's loops, plus what
// the file carries beside it: the campaign, identify's result (a path or the
// embedded result.json) and the version of beamid that wrote it.
// Keys, as `beamid report` and older files know them: format, beamid_version,
// campaign {folder, name}, campaign_sha256 (the campaign's content hash,
// signal/campaign_hash.h), result_file (or "result": a path or the result
// object), selected, verdict, summary, base, final {extension, fit,
// extra_parameter_names}, candidates [{name, description, score, refit
// (RefitStatus), refit_message, significant, extra_parameters {name: {value, std, unit, ci95}},
// extra_parameter_names, residual_before, residual_after, residual_drop,
// likelihood_ratio, test_dof, p_value, seconds, fit}], location (the
// MisfitLocation with its loops, or {error}), response [{level,
// frequency_hz, channel, held_out, measured, base_model, final_model: [re,
// im]}], seconds. A fit: parameters {name: {value, std, unit, ci95: [low,
// high]}} in the model's order, model_harmonics, chi_square,
// degrees_of_freedom, num_residuals, reduced_chi_square, aic, bic,
// held_out_chi_square, held_out_h1_relative_error.
// verdict, ranked_by and blame are the names of DiagnosisVerdict, RankedBy
// and Blame (solver/diagnosis/diagnosis.h).
// The fields are declared once (hb/json_schema.h, in diagnosis_io.cc): the
// declaration writes the file, reads it (a key the format does not have, a
// number outside its range, an unknown verdict are refused, naming the
// field) and lists its fields (DiagnosisFileFields, docs/formats.md).
// Numbers are written with the digits that read back to the same double;
// JSON has no NaN, so a NaN (e.g. a held-out error without held-out
// channels) is written as null and read back as NaN where the field allows
// it. A file of an earlier version, without beamid_version, campaign,
// campaign_sha256, extra_parameter_names, response or a loop step's
// omega_rad_s, still reads (version "", names from the extra_parameters
// keys, no response points, ω from frequency_hz).
#pragma once

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "hb/json_schema.h"
#include "hb/version.h"
#include "solver/diagnosis/diagnosis.h"

namespace beamid::solver {

inline constexpr std::string_view kDiagnosisFormat = "beamid-diagnosis/1";

struct DiagnosisFile {
  DiagnosisResult diagnosis;
  std::string campaign_folder;  // as given to `beamid diagnose`
  std::string campaign_name;
  std::string campaign_sha256;  // the campaign's content hash (signal/campaign_hash.h); "" in older files
  // identify's result.json: a path (absolute as `beamid diagnose --result`
  // writes it; a relative one is relative to the diagnosis file), or the
  // result embedded as JSON text for ResultFileFromJson
  // (solver/estimation/result_io.h). Empty when the file has none.
  std::string result_file;
  std::string embedded_result_json;
  std::string beamid_version = kVersion;  // "" in files older than the key
  // How the phasors were weighed (fit_data.h); older files: the relative floor.
  PhasorUncertainty phasor_uncertainty = PhasorUncertainty::kRelativeFloor;
};

// The fields of the file: path, type, unit, range (docs/formats.md).
std::vector<schema::FieldDoc> DiagnosisFileFields();

std::string DiagnosisFileToJson(const DiagnosisFile& file);
// source names the text in errors (its file). Throws InputError naming the
// source, the field (e.g. candidates[2].fit.chi_square) and the fix.
DiagnosisFile DiagnosisFileFromJson(const std::string& text, const std::string& source);

// Throw InputError when the file cannot be written or read.
void WriteDiagnosisFile(const std::filesystem::path& path, const DiagnosisFile& file);
DiagnosisFile ReadDiagnosisFile(const std::filesystem::path& path);

// One candidate refit (one start) as a worker process hands it back to
// Diagnose: text, every double exact (non-finite ones included), so that a
// diagnosis is the same with any number of workers.
struct CandidateRefit {
  double chi_square = 0.0;
  double seconds = 0.0;           // Ipopt's
  std::vector<double> values;     // the parameters, in the structure's order
  std::vector<double> std;        // their standard uncertainties
  std::vector<double> scaled_at;  // the parameters whose feasible point set x's scales
  std::vector<double> x;          // the optimiser's variables at the optimum
  // A fault of the recording's refit (solver/diagnosis/measurement_artefacts.h):
  // its parameter, the one the data were corrected with, and its std (0 otherwise).
  double artefact_value = 0.0;
  double artefact_std = 0.0;
};

std::string CandidateRefitToText(const CandidateRefit& refit);
// Throws std::runtime_error on text CandidateRefitToText did not write.
CandidateRefit CandidateRefitFromText(const std::string& text);

}  // namespace beamid::solver
