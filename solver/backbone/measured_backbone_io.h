// The file of `beamid backbone --measured` (format
// "beamid-measured-backbone/1", <output>.json) and its one reader and writer,
// driven by one declaration (hb/json_schema.h):
// the measured backbone per level, the chosen single-mode fit with its
// candidates and its curve against amplitude, the damping trend, and the
// identified model's backbone at the sensor when --result was given.
// Keys, as earlier files have them: format, beamid_version, inputs, channel,
// response_quantity, excitation {quantity (force, voltage,
// base_acceleration), unit (its SI unit: force_N and receptance_m_N are then
// per this unit), frf (what X/F is)}, amplitude (a description), levels
// [{label, control,
// num_points, num_fit_points, phase_resonance {frequency_Hz,
// displacement_amplitude_m, response_amplitude, force_N, damping_ratio,
// after_jump, note}, peak {frequency_Hz, receptance_m_N,
// displacement_amplitude_m}, half_power {damping_ratio,
// lower_frequency_Hz, upper_frequency_Hz, natural_frequency_Hz, note}, damping_ratio (the
// reported ζ, its σ covering the three estimators' spread),
// damping_ratio_note, local_fit
// {natural_frequency_Hz, damping_ratio, reduced_chi_square}, regeneration
// {relative_rms, max_relative, reduced_chi_square, noise_relative_rms}, jumps
// [{from_step, to_step (run order, from 0), from_frequency_Hz,
// to_frequency_Hz, direction ("up"/"down"), receptance_ratio (after/before),
// phase_change_rad, miss_over_predicted}], measured_frf [{frequency_Hz,
// receptance_m_N (|X_d/F|), phase_rad (of X_d against F)}] (the steps, run
// order), fit_frf [the same] (the cross-level fit regenerating the level,
// frequency order), flags [{kind
// (damping_not_positive, peak_outside_band, regeneration_beyond_noise, jump,
// phase_convention),
// quantity, message}], in_global_fit}], single_mode_fit {model
// (a description), form, frequency_degree, damping_degree,
// frequency_exponent, damping_exponent, amplitude_dependent_modal_constant,
// residual_receptance_m_N, parameter_order (a description),
// reference_amplitude_m, parameters, reduced_chi_square, candidates, curve},
// damping_trend {amplitude_m, slope_per_m, slope_std_per_m, z (of ζ),
// damping_rate_slope_per_s_m, damping_rate_slope_std_per_s_m,
// damping_rate_z (of ζω_n), verdict (on ζω_n: against a constant damper),
// damping_ratio_verdict (on ζ alone)}, model_backbone [{amplitude_m, frequency_Hz}], warnings.
// An estimate is {value, std}, or null when it could not be made. JSON has no
// NaN: a number that is not finite is written as null and read back as NaN.
// The descriptions (amplitude, model, parameter_order, excitation's unit and
// frf) are written for a reader and not read back. Reading checks every
// field, its type and range (MeasuredBackboneFileFields) and throws
// InputError naming the file, the field (e.g. "levels[2].peak.frequency_Hz")
// and the fix; a key the format does not have is refused; a file without beamid_version reads (version ""), one
// without jumps, measured_frf, fit_frf, flags, in_global_fit,
// noise_relative_rms or excitation (older files) reads as no jumps, no
// curves, no flags, in the fit, 0, a force.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "hb/json_schema.h"
#include "hb/version.h"
#include "solver/backbone/measured_backbone.h"

namespace beamid::solver {

inline constexpr std::string_view kMeasuredBackboneFormat = "beamid-measured-backbone/1";

// One point of the single-mode fit's curve against amplitude.
struct MeasuredBackboneCurvePoint {
  double amplitude_m = 0.0;
  double frequency_hz = 0.0;
  double frequency_std_hz = 0.0;
  double damping_ratio = 0.0;
  double damping_ratio_std = 0.0;
};

// The fit as the file holds it: its form and parameters, not the fit's
// internals (covariance, points), which the file never carried.
struct MeasuredBackboneFit {
  std::string form;  // SingleModeFit::FormName()
  int frequency_degree = 0;
  int damping_degree = 0;
  double frequency_exponent = 0.0;
  double damping_exponent = 0.0;
  bool amplitude_dependent_modal_constant = false;
  double residual_receptance_m_N = 0.0;
  double reference_amplitude_m = 1.0;
  std::vector<double> parameters;  // Re A0, Im A0, [A2], ω_n² terms, ζω_n terms
  double reduced_chi_square = 0.0;
  std::vector<BackboneModelCandidate> candidates;
  std::vector<MeasuredBackboneCurvePoint> curve;  // empty when the fit failed
};

struct MeasuredBackboneModelPoint {
  double amplitude_m = 0.0;
  double frequency_hz = 0.0;
};

struct MeasuredBackboneFile {
  std::string beamid_version = kVersion;  // "" in files older than the key
  std::vector<std::string> inputs;        // as given to --measured
  std::string channel;
  std::string response_quantity;
  std::string excitation_quantity = "force";  // "excitation" in the JSON; files before it: force
  std::vector<LevelResonance> levels;
  MeasuredBackboneFit single_mode_fit;
  DampingTrend damping_trend;
  std::vector<MeasuredBackboneModelPoint> model_backbone;  // empty without --result
  std::vector<std::string> warnings;
};

// The fields of the JSON file: path, type, unit, range (docs/formats.md).
std::vector<schema::FieldDoc> MeasuredBackboneFileFields();

std::string MeasuredBackboneFileToJson(const MeasuredBackboneFile& file);
// `source` names the text in messages (the file it came from).
MeasuredBackboneFile MeasuredBackboneFileFromJson(const std::string& text, const std::string& source);

// Atomically (hb/text_file.h): the old file or the new one, never half.
// Both throw InputError when the file cannot be written or read.
void WriteMeasuredBackboneFile(const std::filesystem::path& path, const MeasuredBackboneFile& file);
MeasuredBackboneFile ReadMeasuredBackboneFile(const std::filesystem::path& path);

}  // namespace beamid::solver
