#include "solver/backbone/measured_backbone_io.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <initializer_list>
#include <limits>
#include <string_view>

#include <nlohmann/json.hpp>

#include "hb/json_field.h"
#include "hb/errors.h"
#include "hb/text_file.h"

namespace beamid::solver {
namespace {

// Insertion order is kept so that a file read and written again is the same text.
using Json = nlohmann::ordered_json;

constexpr const char* kFix = "give a .json written by 'beamid backbone --measured', or repair that field";

// Descriptions for a reader of the file; they are the same in every file, so
// the struct does not carry them.
constexpr const char* kAmplitudeDescription = "first-harmonic displacement amplitude at the sensor [m]";
constexpr const char* kModelDescription =
    "A(a)*F/X_d = wn^2(a) - w^2 + 2i*w*(zeta*wn)(a), s = a/a_ref; wn^2, zeta*wn: polynomials in s or power laws "
    "c0 + c1*s^exponent (Iwan-like); A = A0r + i*A0i (+ A2*s^2); chosen by AICc; X_d/F = A/D + R, a = |X_d - R*F|";
constexpr const char* kParameterOrder = "Re A0, Im A0, [A2], wn^2 terms, zeta*wn terms";

// ---------------------------------------------------------------- writing

Json Number(double v) { return std::isfinite(v) ? Json(v) : Json(nullptr); }

Json EstimateToJson(const Estimate& e) {
  if (!e.valid) return nullptr;
  return {{"value", Number(e.value)}, {"std", Number(e.std)}};
}

Json LevelToJson(const LevelResonance& l) {
  Json flags = Json::array();
  for (const auto& f : l.flags)
    flags.push_back({{"kind", std::string(LevelFlagName(f.kind))}, {"quantity", f.quantity}, {"message", f.message}});
  Json jumps = Json::array();
  for (const auto& j : l.jumps)
    jumps.push_back({{"from_step", j.from_step},
                     {"to_step", j.to_step},
                     {"from_frequency_Hz", Number(j.from_frequency_hz)},
                     {"to_frequency_Hz", Number(j.to_frequency_hz)},
                     {"direction", j.up_sweep ? "up" : "down"},
                     {"receptance_ratio", Number(j.receptance_ratio)},
                     {"phase_change_rad", Number(j.phase_change_rad)},
                     {"miss_over_predicted", Number(j.miss_over_predicted)}});
  return {{"label", l.label},
          {"control", std::string(LevelControlName(l.control))},
          {"num_points", l.num_points},
          {"num_fit_points", l.num_fit_points},
          {"phase_resonance",
           {{"frequency_Hz", EstimateToJson(l.quadrature_frequency_hz)},
            {"displacement_amplitude_m", EstimateToJson(l.quadrature_amplitude_m)},
            {"response_amplitude", EstimateToJson(l.quadrature_response_amplitude)},
            {"force_N", EstimateToJson(l.quadrature_force_N)},
            {"damping_ratio", EstimateToJson(l.quadrature_damping_ratio)},
            {"after_jump", l.quadrature_after_jump},
            {"note", l.quadrature_note}}},
          {"peak",
           {{"frequency_Hz", EstimateToJson(l.peak_frequency_hz)},
            {"receptance_m_N", EstimateToJson(l.peak_receptance_m_N)},
            {"displacement_amplitude_m", EstimateToJson(l.peak_amplitude_m)}}},
          {"half_power",
           {{"damping_ratio", EstimateToJson(l.half_power_damping_ratio)},
            {"lower_frequency_Hz", EstimateToJson(l.half_power_lower_frequency_hz)},
            {"upper_frequency_Hz", EstimateToJson(l.half_power_upper_frequency_hz)},
            {"natural_frequency_Hz", EstimateToJson(l.half_power_natural_frequency_hz)},
            {"note", l.half_power_note}}},
          {"damping_ratio", EstimateToJson(l.damping_ratio)},
          {"damping_ratio_note", l.damping_ratio_note},
          {"local_fit",
           {{"natural_frequency_Hz", EstimateToJson(l.local_natural_frequency_hz)},
            {"damping_ratio", EstimateToJson(l.local_damping_ratio)},
            {"reduced_chi_square", Number(l.local_reduced_chi_square)}}},
          {"regeneration",
           {{"relative_rms", Number(l.regeneration_relative_rms)},
            {"max_relative", Number(l.regeneration_max_relative)},
            {"reduced_chi_square", Number(l.regeneration_reduced_chi_square)},
            {"noise_relative_rms", Number(l.regeneration_noise_relative_rms)}}},
          {"jumps", jumps},
          {"flags", flags},
          {"in_global_fit", l.in_global_fit}};
}

Json FitToJson(const MeasuredBackboneFit& fit) {
  Json parameters = Json::array();
  for (double p : fit.parameters) parameters.push_back(Number(p));
  Json candidates = Json::array();
  for (const auto& c : fit.candidates)
    candidates.push_back({{"form", c.form},
                          {"frequency_degree", c.frequency_degree},
                          {"damping_degree", c.damping_degree},
                          {"frequency_exponent", Number(c.frequency_exponent)},
                          {"damping_exponent", Number(c.damping_exponent)},
                          {"amplitude_dependent_modal_constant", c.amplitude_dependent_modal_constant},
                          {"aicc", Number(c.aicc)},
                          {"reduced_chi_square", Number(c.reduced_chi_square)}});
  Json curve = Json::array();
  for (const auto& p : fit.curve)
    curve.push_back({{"amplitude_m", Number(p.amplitude_m)},
                     {"frequency_Hz", Number(p.frequency_hz)},
                     {"frequency_std_Hz", Number(p.frequency_std_hz)},
                     {"damping_ratio", Number(p.damping_ratio)},
                     {"damping_ratio_std", Number(p.damping_ratio_std)}});
  return {{"model", kModelDescription},
          {"form", fit.form},
          {"frequency_degree", fit.frequency_degree},
          {"damping_degree", fit.damping_degree},
          {"frequency_exponent", Number(fit.frequency_exponent)},
          {"damping_exponent", Number(fit.damping_exponent)},
          {"amplitude_dependent_modal_constant", fit.amplitude_dependent_modal_constant},
          {"residual_receptance_m_N", Number(fit.residual_receptance_m_N)},
          {"parameter_order", kParameterOrder},
          {"reference_amplitude_m", Number(fit.reference_amplitude_m)},
          {"parameters", parameters},
          {"reduced_chi_square", Number(fit.reduced_chi_square)},
          {"candidates", candidates},
          {"curve", curve}};
}

// ---------------------------------------------------------------- reading

using Field = JsonField;

// null: an estimate that could not be made.
Estimate AsEstimate(const Field& f) {
  if (f.json().is_null()) return {};
  f.OnlyKeys({"value", "std"});
  return {.value = f.Number("value"), .std = f.Number("std"), .valid = true};
}

LevelControl ControlFromJson(const Field& f) {
  const std::string name = f.String();
  for (LevelControl c : {LevelControl::kForce, LevelControl::kResponse, LevelControl::kNeither})
    if (name == LevelControlName(c)) return c;
  f.Fail("is \"" + name + "\"", "give \"force\", \"response\" or \"neither\"");
}

LevelResonance LevelFromJson(const Field& f) {
  f.OnlyKeys({"label", "control", "num_points", "num_fit_points", "phase_resonance", "peak", "half_power",
              "damping_ratio", "damping_ratio_note", "local_fit",
              "regeneration", "jumps", "flags", "in_global_fit"});
  LevelResonance l;
  l.label = f.String("label");
  l.control = ControlFromJson(f.At("control"));
  l.num_points = f.Integer("num_points");
  l.num_fit_points = f.Integer("num_fit_points");
  const Field phase = f.At("phase_resonance");
  phase.OnlyKeys({"frequency_Hz", "displacement_amplitude_m", "response_amplitude", "force_N", "damping_ratio",
                  "after_jump", "note"});
  l.quadrature_frequency_hz = AsEstimate(phase.At("frequency_Hz"));
  l.quadrature_amplitude_m = AsEstimate(phase.At("displacement_amplitude_m"));
  l.quadrature_response_amplitude = AsEstimate(phase.At("response_amplitude"));
  l.quadrature_force_N = AsEstimate(phase.At("force_N"));
  l.quadrature_damping_ratio = AsEstimate(phase.At("damping_ratio"));
  l.quadrature_after_jump = phase.Boolean("after_jump");
  l.quadrature_note = phase.String("note");
  const Field peak = f.At("peak");
  peak.OnlyKeys({"frequency_Hz", "receptance_m_N", "displacement_amplitude_m"});
  l.peak_frequency_hz = AsEstimate(peak.At("frequency_Hz"));
  l.peak_receptance_m_N = AsEstimate(peak.At("receptance_m_N"));
  l.peak_amplitude_m = AsEstimate(peak.At("displacement_amplitude_m"));
  const Field half = f.At("half_power");
  half.OnlyKeys({"damping_ratio", "lower_frequency_Hz", "upper_frequency_Hz", "natural_frequency_Hz", "note"});
  l.half_power_damping_ratio = AsEstimate(half.At("damping_ratio"));
  // Files written before the half-power frequencies: none.
  if (half.Has("lower_frequency_Hz")) l.half_power_lower_frequency_hz = AsEstimate(half.At("lower_frequency_Hz"));
  if (half.Has("upper_frequency_Hz")) l.half_power_upper_frequency_hz = AsEstimate(half.At("upper_frequency_Hz"));
  if (half.Has("natural_frequency_Hz"))
    l.half_power_natural_frequency_hz = AsEstimate(half.At("natural_frequency_Hz"));
  l.half_power_note = half.String("note");
  // Files written before the combined damping ratio: none.
  if (f.Has("damping_ratio")) l.damping_ratio = AsEstimate(f.At("damping_ratio"));
  if (f.Has("damping_ratio_note")) l.damping_ratio_note = f.String("damping_ratio_note");
  const Field local = f.At("local_fit");
  local.OnlyKeys({"natural_frequency_Hz", "damping_ratio", "reduced_chi_square"});
  l.local_natural_frequency_hz = AsEstimate(local.At("natural_frequency_Hz"));
  l.local_damping_ratio = AsEstimate(local.At("damping_ratio"));
  l.local_reduced_chi_square = local.Number("reduced_chi_square");
  const Field regeneration = f.At("regeneration");
  regeneration.OnlyKeys({"relative_rms", "max_relative", "reduced_chi_square", "noise_relative_rms"});
  l.regeneration_relative_rms = regeneration.Number("relative_rms");
  l.regeneration_max_relative = regeneration.Number("max_relative");
  l.regeneration_reduced_chi_square = regeneration.Number("reduced_chi_square");
  // Files written before the flags have neither these nor the flags: read as 0, none, in the fit.
  if (regeneration.Has("noise_relative_rms")) l.regeneration_noise_relative_rms = regeneration.Number("noise_relative_rms");
  // Files written before the jump detection have no jumps.
  if (f.Has("jumps")) {
    const Field jumps = f.At("jumps");
    for (std::size_t i = 0; i < jumps.Size(); ++i) {
      const Field j = jumps.At(i);
      j.OnlyKeys({"from_step", "to_step", "from_frequency_Hz", "to_frequency_Hz", "direction", "receptance_ratio",
                  "phase_change_rad", "miss_over_predicted"});
      const Field direction = j.At("direction");
      const std::string d = direction.String();
      if (d != "up" && d != "down") direction.Fail("is \"" + d + "\"", "give \"up\" or \"down\"");
      l.jumps.push_back({.from_step = j.Integer("from_step"),
                         .to_step = j.Integer("to_step"),
                         .from_frequency_hz = j.Number("from_frequency_Hz"),
                         .to_frequency_hz = j.Number("to_frequency_Hz"),
                         .up_sweep = d == "up",
                         .receptance_ratio = j.Number("receptance_ratio"),
                         .phase_change_rad = j.Number("phase_change_rad"),
                         .miss_over_predicted = j.Number("miss_over_predicted")});
    }
  }
  if (f.Has("flags")) {
    const Field flags = f.At("flags");
    for (std::size_t i = 0; i < flags.Size(); ++i) {
      const Field flag = flags.At(i);
      flag.OnlyKeys({"kind", "quantity", "message"});
      const Field kind = flag.At("kind");
      const std::string name = kind.String();
      LevelFlag parsed;
      try {
        parsed.kind = LevelFlagKindFromName(name);
      } catch (const InputError&) {
        kind.Fail("is \"" + name + "\"",
                  "give \"damping_not_positive\", \"peak_outside_band\", \"regeneration_beyond_noise\", \"jump\" or "
                  "\"phase_convention\"");
      }
      parsed.quantity = flag.String("quantity");
      parsed.message = flag.String("message");
      l.flags.push_back(std::move(parsed));
    }
  }
  if (f.Has("in_global_fit")) l.in_global_fit = f.Boolean("in_global_fit");
  return l;
}

MeasuredBackboneFit FitFromJson(const Field& f) {
  f.OnlyKeys({"model", "form", "frequency_degree", "damping_degree", "frequency_exponent", "damping_exponent",
              "amplitude_dependent_modal_constant", "residual_receptance_m_N", "parameter_order",
              "reference_amplitude_m", "parameters", "reduced_chi_square", "candidates", "curve"});
  if (f.Has("model")) f.String("model");
  if (f.Has("parameter_order")) f.String("parameter_order");
  MeasuredBackboneFit fit;
  fit.form = f.String("form");
  fit.frequency_degree = f.Integer("frequency_degree");
  fit.damping_degree = f.Integer("damping_degree");
  fit.frequency_exponent = f.Number("frequency_exponent");
  fit.damping_exponent = f.Number("damping_exponent");
  fit.amplitude_dependent_modal_constant = f.Boolean("amplitude_dependent_modal_constant");
  fit.residual_receptance_m_N = f.Number("residual_receptance_m_N");
  fit.reference_amplitude_m = f.Number("reference_amplitude_m");
  fit.parameters = f.At("parameters").Numbers();
  fit.reduced_chi_square = f.Number("reduced_chi_square");
  const Field candidates = f.At("candidates");
  for (std::size_t i = 0; i < candidates.Size(); ++i) {
    const Field c = candidates.At(i);
    c.OnlyKeys({"form", "frequency_degree", "damping_degree", "frequency_exponent", "damping_exponent",
                "amplitude_dependent_modal_constant", "aicc", "reduced_chi_square"});
    fit.candidates.push_back({.frequency_degree = c.Integer("frequency_degree"),
                              .damping_degree = c.Integer("damping_degree"),
                              .aicc = c.Number("aicc"),
                              .reduced_chi_square = c.Number("reduced_chi_square"),
                              .frequency_exponent = c.Number("frequency_exponent"),
                              .damping_exponent = c.Number("damping_exponent"),
                              .amplitude_dependent_modal_constant = c.Boolean("amplitude_dependent_modal_constant"),
                              .form = c.String("form")});
  }
  const Field curve = f.At("curve");
  for (std::size_t i = 0; i < curve.Size(); ++i) {
    const Field p = curve.At(i);
    p.OnlyKeys({"amplitude_m", "frequency_Hz", "frequency_std_Hz", "damping_ratio", "damping_ratio_std"});
    fit.curve.push_back({.amplitude_m = p.Number("amplitude_m"),
                         .frequency_hz = p.Number("frequency_Hz"),
                         .frequency_std_hz = p.Number("frequency_std_Hz"),
                         .damping_ratio = p.Number("damping_ratio"),
                         .damping_ratio_std = p.Number("damping_ratio_std")});
  }
  return fit;
}

}  // namespace

std::string MeasuredBackboneFileToJson(const MeasuredBackboneFile& file) {
  Json levels = Json::array();
  for (const auto& l : file.levels) levels.push_back(LevelToJson(l));
  Json model = Json::array();
  for (const auto& p : file.model_backbone)
    model.push_back({{"amplitude_m", Number(p.amplitude_m)}, {"frequency_Hz", Number(p.frequency_hz)}});
  const auto& trend = file.damping_trend;
  const Json root = {{"format", std::string(kMeasuredBackboneFormat)},
                     {"beamid_version", file.beamid_version},
                     {"inputs", file.inputs},
                     {"channel", file.channel},
                     {"response_quantity", file.response_quantity},
                     {"excitation",
                      {{"quantity", file.excitation_quantity},
                       {"unit", LabelsOf(file.excitation_quantity).unit},
                       {"frf", LabelsOf(file.excitation_quantity).frf}}},
                     {"amplitude", kAmplitudeDescription},
                     {"levels", levels},
                     {"single_mode_fit", FitToJson(file.single_mode_fit)},
                     {"damping_trend",
                      {{"amplitude_m", Number(trend.amplitude_m)},
                       {"slope_per_m", Number(trend.slope_per_m)},
                       {"slope_std_per_m", Number(trend.slope_std_per_m)},
                       {"z", Number(trend.z)},
                       {"damping_rate_slope_per_s_m", Number(trend.damping_rate_slope_per_s_m)},
                       {"damping_rate_slope_std_per_s_m", Number(trend.damping_rate_slope_std_per_s_m)},
                       {"damping_rate_z", Number(trend.damping_rate_z)},
                       {"verdict", trend.verdict},
                       {"damping_ratio_verdict", trend.damping_ratio_verdict}}},
                     {"model_backbone", model},
                     {"warnings", file.warnings}};
  return root.dump(1) + "\n";
}

MeasuredBackboneFile MeasuredBackboneFileFromJson(const std::string& text, const std::string& source) {
  const Json json =
      ParseJsonObject(text, source, "measured backbone", "give a .json written by 'beamid backbone --measured'");
  const Field root(json, "", source, kMeasuredBackboneFormat, kFix);
  const std::string format = root.String("format");
  if (format != kMeasuredBackboneFormat)
    throw InputError(source + ": field \"format\" is \"" + format + "\", not \"" +
                     std::string(kMeasuredBackboneFormat) +
                     "\". Fix: give a .json written by 'beamid backbone --measured'");
  root.OnlyKeys({"format", "beamid_version", "inputs", "channel", "response_quantity", "excitation", "amplitude", "levels",
                 "single_mode_fit", "damping_trend", "model_backbone", "warnings"});
  MeasuredBackboneFile file;
  file.beamid_version = root.Has("beamid_version") ? root.String("beamid_version") : "";
  file.inputs = root.At("inputs").Strings();
  file.channel = root.String("channel");
  file.response_quantity = root.String("response_quantity");
  if (root.Has("excitation")) {
    const Field excitation = root.At("excitation");
    file.excitation_quantity = excitation.String("quantity");
    LabelsOf(file.excitation_quantity);  // refuses an unknown one
  }
  if (root.Has("amplitude")) root.String("amplitude");
  const Field levels = root.At("levels");
  for (std::size_t i = 0; i < levels.Size(); ++i) file.levels.push_back(LevelFromJson(levels.At(i)));
  file.single_mode_fit = FitFromJson(root.At("single_mode_fit"));
  const Field trend = root.At("damping_trend");
  trend.OnlyKeys({"amplitude_m", "slope_per_m", "slope_std_per_m", "z", "damping_rate_slope_per_s_m",
                  "damping_rate_slope_std_per_s_m", "damping_rate_z", "verdict", "damping_ratio_verdict"});
  file.damping_trend = {.amplitude_m = trend.Number("amplitude_m"),
                        .slope_per_m = trend.Number("slope_per_m"),
                        .slope_std_per_m = trend.Number("slope_std_per_m"),
                        .z = trend.Number("z"),
                        .verdict = trend.String("verdict")};
  // Files written before the damping rate judged ζ alone: their verdict was on ζ.
  auto& t = file.damping_trend;
  if (trend.Has("damping_rate_z")) {
    t.damping_rate_slope_per_s_m = trend.Number("damping_rate_slope_per_s_m");
    t.damping_rate_slope_std_per_s_m = trend.Number("damping_rate_slope_std_per_s_m");
    t.damping_rate_z = trend.Number("damping_rate_z");
    t.damping_ratio_verdict = trend.String("damping_ratio_verdict");
  } else {
    t.damping_ratio_verdict = t.verdict;
  }
  const Field model = root.At("model_backbone");
  for (std::size_t i = 0; i < model.Size(); ++i) {
    const Field p = model.At(i);
    p.OnlyKeys({"amplitude_m", "frequency_Hz"});
    file.model_backbone.push_back({.amplitude_m = p.Number("amplitude_m"), .frequency_hz = p.Number("frequency_Hz")});
  }
  file.warnings = root.At("warnings").Strings();
  return file;
}

void WriteMeasuredBackboneFile(const std::filesystem::path& path, const MeasuredBackboneFile& file) {
  WriteTextFileAtomically(path, MeasuredBackboneFileToJson(file));
}

MeasuredBackboneFile ReadMeasuredBackboneFile(const std::filesystem::path& path) {
  return MeasuredBackboneFileFromJson(
      ReadTextFile(path, "measured backbone file", "give the .json of 'beamid backbone --measured', or check the path"),
      path.string());
}

}  // namespace beamid::solver
