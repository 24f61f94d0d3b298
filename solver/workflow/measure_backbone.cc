#include "solver/workflow/measure_backbone.h"

#include <cmath>
#include <filesystem>
#include <numbers>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string_view>

#include <fmt/core.h>

#include "hb/csv_cell.h"
#include "hb/file_stem.h"
#include "hb/errors.h"
#include "hb/version.h"
#include "signal/array_file.h"
#include "signal/campaign.h"
#include "signal/campaign_extractor.h"
#include "signal/first_harmonic_level.h"
#include "signal/phasor_set_io.h"
#include "signal/phasor_table.h"
#include "signal/uff58_export.h"
#include "signal/uff58_level.h"
#include "solver/backbone/measured_backbone_csv.h"
#include "solver/backbone/measured_backbone_io.h"
#include "solver/estimation/prediction.h"
#include "solver/workflow/campaign_input.h"
#include "solver/workflow/output_file.h"
#include "solver/workflow/output_paths.h"

namespace beamid::workflow {
namespace {

std::vector<signal::FirstHarmonicLevel> ReadLevels(const MeasureBackboneRequest& options, const RunObserver& observer) {
  namespace fs = std::filesystem;
  const fs::path first = options.inputs.front();
  const bool universal = signal::IsUniversalFile(first);
  // A .mat or HDF5 file of a level is a first-harmonic table of vectors (signal/phasor_table.h).
  const bool arrays = signal::IsArrayFile(first);
  const bool tables = first.extension() == ".csv" || first.extension() == ".CSV" || first.extension() == ".txt" ||
                      universal || arrays;
  if (!fs::is_directory(first) && options.skip_bad_steps)
    throw InputError("--skip-bad-steps applies to a campaign folder (whose recordings are extracted here), not to " +
                     first.string() + ". Fix: drop --skip-bad-steps, or give the campaign folder");
  const signal::PhasorTableOptions& table = options.table;
  if ((!tables || universal) &&
      (table.layout.lines_before_header > 0 || table.layout.units_row || !table.columns.Empty()))
    throw InputError("--lines-before-header, --units-row and --column apply to first-harmonic CSV tables, not to " +
                     first.string() + ". Fix: drop them; a campaign declares its recordings' layout and columns in "
                     "campaign.json (recording_layout, each channel's column)");
  if (arrays && (table.layout.lines_before_header > 0 || table.layout.units_row))
    throw InputError("--lines-before-header and --units-row apply to first-harmonic CSV tables, not to " +
                     first.string() + ". Fix: drop them; a .mat or HDF5 table's units are its vectors' names or "
                     "units (docs/phasor-table.md)");
  if (tables) {
    if (!options.channel.empty())
      throw InputError("--channel " + options.channel + ": a first-harmonic table holds one response, named by its "
                       "columns. Fix: drop --channel, or give a campaign folder or phasor file");
    std::vector<signal::FirstHarmonicLevel> levels;
    for (const auto& input : options.inputs) {
      levels.push_back(signal::IsUniversalFile(input) ? signal::ReadUff58Level(input)
                                                      : signal::ReadPhasorTable(input, table));
      levels.back().response_position_m = options.position_m;
    }
    return levels;
  }
  if (options.inputs.size() > 1)
    throw std::invalid_argument("--measured: give one campaign folder or phasor file, or several CSV tables");
  signal::PhasorSet set;
  std::string channel = options.channel;
  if (fs::is_directory(first)) {
    signal::Campaign campaign = ReadCampaignAndWarn("backbone", first, observer);
    if (channel.empty())
      for (const auto& sensor : campaign.sensors)
        if (channel.empty() && campaign.Use(sensor.channel) != signal::ChannelUse::kIgnored) channel = sensor.channel;
    // Only the backbone's channel (and the excitation) may stop a step: a
    // broken sensor it does not read is a warning, as with `extract --channel`.
    if (!channel.empty()) campaign.Analyse({channel});
    signal::ExtractOptions extract;
    extract.estimator.num_harmonics = 3;
    extract.skip_bad_steps = options.skip_bad_steps;
    set = signal::ExtractCampaign(campaign, extract);
    WarnSkippedSteps("backbone", set, observer);
  } else {
    set = signal::ReadPhasorSetJson(first);
  }
  if (set.steps.empty() || set.steps.front().responses.empty())
    throw std::invalid_argument(first.string() + ": no steps with a response channel");
  if (channel.empty()) channel = set.steps.front().responses.front().channel;
  if (options.channel.empty()) observer.Note("backbone: response channel " + channel + " (--channel to choose)");
  return signal::FirstHarmonicLevels(set, channel, first.string());
}

}  // namespace

void MeasureBackboneRequest::Validate() const {
  if (inputs.empty())
    throw InputError("--measured: no input. Fix: give a campaign folder, a phasor file of beamid extract, or "
                     "first-harmonic CSV tables (one per level)");
  if (!(position_m < 0.0) && !(position_m >= 0.0 && position_m <= 100.0))
    throw InputError("--position-m " + std::to_string(position_m) +
                     ": must be a finite number in 0 … 100 (the sensor's position on the beam in metres)");
  // -o naming an input itself (a prefix: nothing would be overwritten, but surely a slip).
  for (const auto& input : inputs) {
    std::error_code error;
    const auto canonical = [&](const std::filesystem::path& p) {
      return std::filesystem::weakly_canonical(std::filesystem::absolute(p), error);
    };
    if (canonical(output) == canonical(input))
      throw InputError("-o " + output + " is also an input of this command (" + input +
                       "): -o takes the prefix of the outputs; choose another name");
  }
  OutputPaths paths;
  for (const auto& input : inputs) {
    if (std::filesystem::is_directory(input))
      paths.InputFolder(input);
    else
      paths.Input(input);
  }
  paths.Input(result_file);
  paths.OutputPrefix("-o", output, {".csv", "_curves.csv", ".json"});
  if (!uff_folder.empty()) paths.OutputFolder("--uff", uff_folder);
  paths.Check();
}

std::string LevelControlText(const solver::MeasuredBackbone& measured, const solver::LevelResonance& level) {
  return solver::LevelControlText(measured.excitation_quantity, level.control);
}

MeasureBackboneOutcome MeasureBackbone(const MeasureBackboneRequest& options, const RunObserver& observer) {
  options.Validate();
  const auto levels = ReadLevels(options, observer);
  if (!options.uff_folder.empty()) {
    std::filesystem::create_directories(options.uff_folder);
    std::set<std::string> taken;
    for (const signal::FirstHarmonicLevel& level : levels)
      WriteTextFile(std::filesystem::path(options.uff_folder) / (hb::UniqueFileStem(level.label, "level_", taken) + ".uff"),
                    signal::Uff58LevelText(level));
  }
  MeasureBackboneOutcome out{
      .measured = solver::AnalyseMeasuredBackbone(levels, {.keep_flagged_levels_in_fit = options.keep_flagged_levels}),
      .channel = levels.front().channel,
      .model_backbone = {},
      .output = options.output};
  const solver::MeasuredBackbone& measured = out.measured;
  std::vector<solver::SensorBackbonePoint>& model = out.model_backbone;
  if (!options.result_file.empty()) {
    const double position = levels.front().response_position_m;
    if (position < 0)
      throw std::invalid_argument("--result: the tables do not say where the sensor is. Fix: give --position-m");
    const solver::IdentifiedModel identified = solver::ReadIdentifiedModel(options.result_file);
    if (!(position >= 0.0 && position <= identified.beam.beam.length_m))
      throw InputError("--position-m " + std::to_string(position) + " lies off the beam of " + options.result_file +
                       " (0 to " + std::to_string(identified.beam.beam.length_m) +
                       " m). Fix: give the sensor's position on the beam in metres");
    model = solver::ModelBackboneAtSensor(identified.structure.ApplyLinear(identified.beam), *identified.structure.law,
                                          identified.force_position_m, position,
                                          {.min_theta_amplitude_rad = 1e-5, .max_theta_amplitude_rad = 3e-2, .num_points = 120});
  }

  // The single-mode fit against amplitude, and the model beside it.
  std::ostringstream curves;
  curves << "amplitude_m,fit_frequency_Hz,fit_frequency_std_Hz,fit_damping_ratio,fit_damping_ratio_std,model_frequency_Hz\n";
  const auto& fit = measured.fit;
  solver::MeasuredBackboneFit fit_file;
  constexpr int kCurvePoints = 60;
  for (int k = 0; fit.ok && k <= kCurvePoints; ++k) {
    const double a = measured.min_amplitude_m + (measured.max_amplitude_m - measured.min_amplitude_m) * k / kCurvePoints;
    const double f = fit.NaturalFrequency_rad_s(a) / (2 * std::numbers::pi);
    const double f_std = fit.NaturalFrequencyStd_rad_s(a) / (2 * std::numbers::pi);
    const double model_f = model.empty() ? NAN : solver::BackboneFrequencyAt_hz(model, a);
    curves << fmt::format("{},{},{},{},{},{}\n", hb::CsvNumber(a, "{:.9g}"), hb::CsvNumber(f, "{:.9g}"),
                          hb::CsvNumber(f_std, "{:.3g}"), hb::CsvNumber(fit.DampingRatio(a), "{:.6g}"),
                          hb::CsvNumber(fit.DampingRatioStd(a), "{:.3g}"), hb::CsvNumber(model_f, "{:.9g}"));
    fit_file.curve.push_back({.amplitude_m = a,
                              .frequency_hz = f,
                              .frequency_std_hz = f_std,
                              .damping_ratio = fit.DampingRatio(a),
                              .damping_ratio_std = fit.DampingRatioStd(a)});
  }
  fit_file.form = fit.FormName();
  fit_file.frequency_degree = fit.frequency_degree;
  fit_file.damping_degree = fit.damping_degree;
  fit_file.frequency_exponent = fit.frequency_exponent;
  fit_file.damping_exponent = fit.damping_exponent;
  fit_file.amplitude_dependent_modal_constant = fit.amplitude_dependent_modal_constant;
  fit_file.residual_receptance_m_N = fit.residual_receptance_m_N;
  fit_file.reference_amplitude_m = fit.reference_amplitude_m;
  fit_file.parameters.assign(fit.parameters.data(), fit.parameters.data() + fit.parameters.size());
  fit_file.reduced_chi_square = fit.ReducedChiSquare();
  fit_file.candidates = measured.candidates;
  const auto& trend = measured.damping_trend;
  solver::MeasuredBackboneFile file{.beamid_version = kVersion,
                                    .inputs = options.inputs,
                                    .channel = levels.front().channel,
                                    .response_quantity = measured.response_quantity,
                                    .excitation_quantity = measured.excitation_quantity,
                                    .levels = measured.levels,
                                    .single_mode_fit = std::move(fit_file),
                                    .damping_trend = trend,
                                    .model_backbone = {},
                                    .warnings = measured.warnings};
  for (const auto& p : model)
    file.model_backbone.push_back({.amplitude_m = p.amplitude_m, .frequency_hz = p.frequency_hz});
  WriteTextFile(options.output + ".csv", solver::MeasuredLevelsCsv(measured));
  WriteTextFile(options.output + "_curves.csv", curves.str());
  solver::WriteMeasuredBackboneFile(options.output + ".json", file);
  return out;
}

}  // namespace beamid::workflow
