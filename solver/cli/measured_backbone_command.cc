#include "solver/cli/measured_backbone_command.h"

#include <cmath>
#include <filesystem>
#include <numbers>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string_view>
#include <tuple>

#include <fmt/core.h>
#include "hb/version.h"
#include "signal/campaign.h"
#include "signal/campaign_extractor.h"
#include "signal/first_harmonic_level.h"
#include "signal/phasor_set_io.h"
#include "signal/phasor_table.h"
#include "solver/cli/cli_output.h"
#include "solver/workflow/output_file.h"
#include "solver/workflow/output_paths.h"
#include "solver/backbone/measured_backbone.h"
#include "solver/backbone/measured_backbone_io.h"
#include "solver/estimation/prediction.h"
#include "solver/backbone/sensor_backbone.h"

namespace beamid::cli {
namespace {

std::vector<signal::FirstHarmonicLevel> ReadLevels(const MeasuredBackboneCommandOptions& options, const GlobalOptions& global) {
  namespace fs = std::filesystem;
  const fs::path first = options.inputs.front();
  const bool tables = first.extension() == ".csv" || first.extension() == ".CSV" || first.extension() == ".txt";
  if (tables) {
    std::vector<signal::FirstHarmonicLevel> levels;
    for (const auto& input : options.inputs) {
      levels.push_back(signal::ReadPhasorTable(input));
      levels.back().response_position_m = options.position_m;
    }
    return levels;
  }
  if (options.inputs.size() > 1)
    throw std::invalid_argument("--measured: give one campaign folder or phasor file, or several CSV tables");
  signal::PhasorSet set;
  if (fs::is_directory(first)) {
    signal::ExtractOptions extract;
    extract.estimator.num_harmonics = 3;
    set = signal::ExtractCampaign(ReadCampaignAndWarn("backbone", first, global), extract);
  } else {
    set = signal::ReadPhasorSetJson(first);
  }
  if (set.steps.empty() || set.steps.front().responses.empty())
    throw std::invalid_argument(first.string() + ": no steps with a response channel");
  const std::string channel = options.channel.empty() ? set.steps.front().responses.front().channel : options.channel;
  if (!global.quiet && options.channel.empty()) PrintToStderr(fmt::format("backbone: response channel {} (--channel to choose)\n", channel));
  return signal::FirstHarmonicLevels(set, channel, first.string());
}

std::string Cell(const solver::Estimate& e) {
  return e.valid ? fmt::format("{:.9g},{:.3g}", e.value, e.std) : ",";
}

}  // namespace

void RunMeasuredBackbone(const MeasuredBackboneCommandOptions& options, const GlobalOptions& global) {
  // -o naming an input itself (a prefix: nothing would be overwritten, but surely a slip).
  for (const auto& input : options.inputs) {
    std::error_code error;
    const auto canonical = [&](const std::filesystem::path& p) {
      return std::filesystem::weakly_canonical(std::filesystem::absolute(p), error);
    };
    if (canonical(options.output) == canonical(input))
      throw InputError("-o " + options.output + " is also an input of this command (" + input +
                       "): -o takes the prefix of the outputs; choose another name");
  }
  workflow::OutputPaths paths;
  for (const auto& input : options.inputs) {
    if (std::filesystem::is_directory(input))
      paths.InputFolder(input);
    else
      paths.Input(input);
  }
  paths.Input(options.result_file);
  paths.OutputPrefix("-o", options.output, {".csv", "_curves.csv", ".json"}).Check();
  const auto levels = ReadLevels(options, global);
  const solver::MeasuredBackbone measured =
      solver::AnalyseMeasuredBackbone(levels, {.keep_flagged_levels_in_fit = options.keep_flagged_levels});

  std::vector<solver::SensorBackbonePoint> model;
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

  // Per level, labelled for what drives it.
  const solver::ExcitationLabels excitation = solver::LabelsOf(measured.excitation_quantity);
  const auto control = [&](const solver::LevelResonance& l) {
    return l.control == solver::LevelControl::kForce ? excitation.control : std::string(solver::LevelControlName(l.control));
  };
  std::ostringstream csv;
  const std::string excitation_std = excitation.column.substr(0, excitation.column.rfind('_')) + "_std" +
                                     excitation.column.substr(excitation.column.rfind('_'));
  csv << "level,control,quadrature_frequency_Hz,quadrature_frequency_std_Hz,amplitude_m,amplitude_std_m,"
         "response_amplitude,response_amplitude_std," << excitation.column << "," << excitation_std
      << ",zeta_quadrature,zeta_quadrature_std,"
         "zeta_local,zeta_local_std,zeta_half_power,zeta_half_power_std,peak_frequency_Hz,peak_frequency_std_Hz,"
         "local_natural_frequency_Hz,local_natural_frequency_std_Hz,regeneration_relative_rms,in_global_fit,flags,"
         "zeta,zeta_std\n";
  for (const auto& l : measured.levels) {
    // The flags' names, ';'-separated (the messages are in the .json).
    std::string flags;
    for (const auto& f : l.flags) {
      const std::string name(solver::LevelFlagName(f.kind));
      if (flags.find(name) == std::string::npos) flags += (flags.empty() ? "" : ";") + name;
    }
    csv << fmt::format("{},{},{},{},{},{},{},{},{},{},{},{:.4g},{},{},{}\n", l.label, control(l),
                       Cell(l.quadrature_frequency_hz), Cell(l.quadrature_amplitude_m),
                       Cell(l.quadrature_response_amplitude), Cell(l.quadrature_force_N),
                       Cell(l.quadrature_damping_ratio), Cell(l.local_damping_ratio), Cell(l.half_power_damping_ratio),
                       Cell(l.peak_frequency_hz), Cell(l.local_natural_frequency_hz), l.regeneration_relative_rms,
                       l.in_global_fit ? 1 : 0, flags, Cell(l.damping_ratio));
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
    curves << fmt::format("{:.9g},{:.9g},{:.3g},{:.6g},{:.3g},{}\n", a, f, f_std, fit.DampingRatio(a),
                          fit.DampingRatioStd(a), std::isfinite(model_f) ? fmt::format("{:.9g}", model_f) : "");
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
  workflow::WriteTextFile(options.output + ".csv", csv.str());
  workflow::WriteTextFile(options.output + "_curves.csv", curves.str());
  solver::WriteMeasuredBackboneFile(options.output + ".json", file);
  if (global.quiet) return;
  for (const auto& w : measured.warnings) PrintToStderr(fmt::format("beamid backbone: warning: {}\n", w));
  // A flag's note, with a space before it, next to the number it concerns.
  const auto note = [](const solver::LevelResonance& l, std::string_view quantity) {
    const std::string text = l.FlagNote(quantity);
    return text.empty() ? text : "  " + text;
  };
  if (measured.excitation_quantity != "force")
    fmt::print("  excitation: {} [{}]; X/F is the {}; {}\n", excitation.control, excitation.unit, excitation.frf,
               excitation.caveat);
  for (const auto& l : measured.levels) {
    if (!l.quadrature_frequency_hz.valid)
      fmt::print("  {:>8} ({}-controlled): no phase resonance ({}), local fit ζ {}{}\n", l.label,
                 control(l), l.quadrature_note,
                 l.local_damping_ratio.valid ? fmt::format("{:.5f}", l.local_damping_ratio.value) : std::string("not available"),
                 note(l, "local_damping_ratio"));
    else
      fmt::print("  {:>8} ({}-controlled): {:.4f} ± {:.4f} Hz{} at {:.3e} m, ζ = {} (phase resonance {:.5f} ± {:.2g}{}, "
                 "local fit {}{}, half-power {}{})\n",
                 l.label, control(l), l.quadrature_frequency_hz.value,
                 l.quadrature_frequency_hz.std, note(l, "quadrature_frequency"), l.quadrature_amplitude_m.value,
                 l.damping_ratio.valid ? fmt::format("{:.5f} ± {:.2g}", l.damping_ratio.value, l.damping_ratio.std)
                                       : std::string("not available"),
                 l.quadrature_damping_ratio.value, l.quadrature_damping_ratio.std,
                 note(l, "quadrature_damping_ratio"),
                 l.local_damping_ratio.valid ? fmt::format("{:.5f}", l.local_damping_ratio.value)
                                             : std::string("not available: too few steps near the mode"),
                 note(l, "local_damping_ratio"),
                 l.half_power_damping_ratio.valid ? fmt::format("{:.5f}", l.half_power_damping_ratio.value)
                                                  : std::string("not available"),
                 note(l, "half_power_damping_ratio"));
    if (!l.damping_ratio_note.empty()) fmt::print("           ζ: {}\n", l.damping_ratio_note);
    if (l.flags.empty()) continue;
    for (const auto& [quantity, what, estimate] :
         {std::tuple{"peak_frequency", "peak", l.peak_frequency_hz},
          std::tuple{"local_natural_frequency", "local-fit natural frequency", l.local_natural_frequency_hz}})
      if (!l.FlagNote(quantity).empty())
        fmt::print("           {} = {}{}\n", what,
                   estimate.valid ? fmt::format("{:.4f} ± {:.2g} Hz", estimate.value, estimate.std) : "none in the band",
                   note(l, quantity));
    if (!l.FlagNote("half_power_damping_ratio").empty())
      fmt::print("           ζ (half-power) = {:.3f} %{}\n", 100 * l.half_power_damping_ratio.value,
                 note(l, "half_power_damping_ratio"));
    for (const auto& f : l.flags)
      if (f.kind == solver::LevelFlagKind::kJump) fmt::print("           jump: {}  [FLAG: jump]\n", f.message);
    for (const auto& f : l.flags)
      if (f.kind == solver::LevelFlagKind::kPhaseConvention)
        fmt::print("           phase: {}  [FLAG: phase convention]\n", f.message);
    if (!l.FlagNote("regeneration_relative_rms").empty())
      fmt::print("           regeneration RMS = {:.3g} % ({}){}\n", 100 * l.regeneration_relative_rms,
                 l.regeneration_noise_relative_rms > 0
                     ? fmt::format("noise {:.3g} %", 100 * l.regeneration_noise_relative_rms)
                     : std::string("no noise given"),
                 note(l, "regeneration_relative_rms"));
    fmt::print("           {}\n", l.in_global_fit ? "flagged, kept in the cross-level fit"
                                                   : "flagged: left out of the cross-level fit and the damping trend");
  }
  if (fit.ok) fmt::print("  single-mode fit (AICc): {}, reduced χ² {:.3g}\n", fit.FormName(), fit.ReducedChiSquare());
  fmt::print("  damping against amplitude: {} (ζω_n: slope {:.3g} ± {:.2g} /(s·m), {:+.1f} σ; ζ alone {}: slope "
             "{:.3g} ± {:.2g} per m, {:+.1f} σ, which a constant damper also gives where the frequency changes)\n",
             schema::NameOf(trend.verdict, solver::kDampingRateTrendNames), trend.damping_rate_slope_per_s_m,
             trend.damping_rate_slope_std_per_s_m, trend.damping_rate_z,
             schema::NameOf(trend.damping_ratio_verdict, solver::kDampingRatioTrendNames), trend.slope_per_m, trend.slope_std_per_m, trend.z);
  fmt::print("wrote {0}.json, {0}.csv and {0}_curves.csv\n", options.output);
}

}  // namespace beamid::cli
