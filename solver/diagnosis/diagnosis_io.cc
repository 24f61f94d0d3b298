#include "solver/diagnosis/diagnosis_io.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <initializer_list>
#include <limits>
#include <numbers>
#include <sstream>
#include <stdexcept>
#include <string_view>

#include <nlohmann/json.hpp>

#include "hb/json_field.h"
#include "hb/errors.h"
#include "hb/text_file.h"

namespace beamid::solver {
namespace {

// Insertion order is kept so that the parameters stay in the model's order
// (and a file read and written again is the same text).
using Json = nlohmann::ordered_json;

constexpr const char* kFix = "give a diagnosis.json written by 'beamid diagnose', or repair that field";

// ---------------------------------------------------------------- writing

Json Number(double v) { return std::isnan(v) ? Json(nullptr) : Json(v); }

Json Numbers(const std::vector<double>& values) {
  Json out = Json::array();
  for (double v : values) out.push_back(Number(v));
  return out;
}

Json ParameterToJson(const ParameterEstimate& p) {
  return {{"value", Number(p.value)},
          {"std", Number(p.std)},
          {"unit", p.unit},
          {"ci95", Json::array({Number(p.lower_95), Number(p.upper_95)})}};
}

Json FitToJson(const FitSummary& s) {
  Json parameters = Json::object();
  for (const auto& p : s.parameters) parameters[p.name] = ParameterToJson(p);
  return {{"parameters", parameters},
          {"model_harmonics", s.model_harmonics},
          {"chi_square", Number(s.chi_square)},
          {"degrees_of_freedom", s.degrees_of_freedom},
          {"num_residuals", s.num_residuals},
          {"reduced_chi_square", Number(s.reduced_chi_square)},
          {"aic", Number(s.aic)},
          {"bic", Number(s.bic)},
          {"held_out_chi_square", Number(s.held_out_chi_square)},
          {"held_out_h1_relative_error", Number(s.held_out_h1_relative_error)},
          {"held_out_num_residuals", s.held_out_num_residuals}};
}

Json LoopsToJson(const LoopEvidence& loops) {
  Json steps = Json::array();
  for (const LoopStep& s : loops.steps) {
    steps.push_back({{"level", s.level},
                     {"frequency_hz", Number(s.omega_rad_s / (2.0 * std::numbers::pi))},
                     // exact ω: frequency_hz·2π need not give it back
                     {"omega_rad_s", Number(s.omega_rad_s)},
                     {"theta_amplitude_rad", Number(s.theta_amplitude_rad)},
                     {"theta_std_rad", Number(s.theta_std_rad)},
                     {"moment_amplitude_Nm", Number(s.moment_amplitude_Nm)},
                     {"dissipated_energy_J", Number(s.dissipated_energy_J)},
                     {"dissipated_energy_std_J", Number(s.dissipated_energy_std_J)},
                     {"viscous_energy_J", Number(s.viscous_energy_J)},
                     {"equivalent_damping_Nms_rad", Number(s.equivalent_damping_Nms_rad)},
                     {"equivalent_damping_std_Nms_rad", Number(s.equivalent_damping_std_Nms_rad)},
                     {"moment_harmonic_ratio", Number(s.moment_harmonic_ratio)},
                     {"elastic_harmonic_chi2", Number(s.elastic_harmonic_chi2)},
                     {"hysteretic_harmonic_chi2", Number(s.hysteretic_harmonic_chi2)},
                     {"harmonic_dof", s.harmonic_dof},
                     {"theta_even_fraction", Number(s.theta_even_fraction)},
                     {"moment_even_fraction", Number(s.moment_even_fraction)}});
  }
  return {{"steps", steps},
          {"num_steps_used", loops.num_steps_used},
          {"area_exponent", Number(loops.area_exponent)},
          {"area_exponent_std", Number(loops.area_exponent_std)},
          {"viscous_chi2", Number(loops.viscous_chi2)},
          {"viscous_dof", loops.viscous_dof},
          {"viscous_p_value", Number(loops.viscous_p_value)},
          {"mean_equivalent_damping_Nms_rad", Number(loops.mean_equivalent_damping_Nms_rad)},
          {"damping_ratio_high_to_low", Number(loops.damping_ratio_high_to_low)},
          {"elastic_harmonic_chi2", Number(loops.elastic_harmonic_chi2)},
          {"hysteretic_harmonic_chi2", Number(loops.hysteretic_harmonic_chi2)},
          {"harmonic_dof", loops.harmonic_dof},
          {"elastic_harmonic_p_value", Number(loops.elastic_harmonic_p_value)},
          {"hysteretic_harmonic_p_value", Number(loops.hysteretic_harmonic_p_value)},
          {"max_moment_harmonic_ratio", Number(loops.max_moment_harmonic_ratio)},
          {"theta_even_chi2", Number(loops.theta_even_chi2)},
          {"theta_even_dof", loops.theta_even_dof},
          {"theta_even_p_value", Number(loops.theta_even_p_value)},
          {"dissipation_not_viscous", loops.dissipation_not_viscous},
          {"non_elliptic", loops.non_elliptic},
          {"hysteretic_shape", loops.hysteretic_shape},
          {"asymmetric", loops.asymmetric}};
}

Json LocationToJson(const MisfitLocation& location) {
  Json groups = Json::array();
  for (const MisfitGroupTest& g : location.groups) {
    groups.push_back({{"channel", g.channel},
                      {"harmonic", g.harmonic},
                      {"level", g.level},
                      {"part", g.part},
                      {"band", g.band},
                      {"chi2", Number(g.chi2)},
                      {"dof", g.dof},
                      {"p_value", Number(g.p_value)},
                      {"adjusted_p_value", Number(g.adjusted_p_value)},
                      {"significant", g.significant},
                      {"excess_chi2", Number(g.excess_chi2)},
                      {"growth_exponent", Number(g.growth_exponent)}});
  }
  return {{"chi2", Number(location.chi2)},
          {"dof", location.dof},
          {"p_value", Number(location.p_value)},
          {"significant", location.significant},
          {"num_groups_tested", location.num_groups_tested},
          {"in_phase_fraction", Number(location.in_phase_fraction)},
          {"near_resonance_fraction", Number(location.near_resonance_fraction)},
          {"fundamental_fraction", Number(location.fundamental_fraction)},
          {"even_harmonic_fraction", Number(location.even_harmonic_fraction)},
          {"beyond_fitted_fraction", Number(location.beyond_fitted_fraction)},
          {"harmonic_excess_chi2", Numbers(location.harmonic_excess_chi2)},
          {"channel_excess_chi2", Numbers(location.channel_excess_chi2)},
          {"level_growth_exponent", Number(location.level_growth_exponent)},
          {"level_misfit_amplitude", Numbers(location.level_misfit_amplitude)},
          {"level_response_amplitude", Numbers(location.level_response_amplitude)},
          {"loops", LoopsToJson(location.loops)},
          {"findings", location.findings},
          {"groups", groups}};
}

Json CandidateToJson(const CandidateOutcome& c, double residual_before) {
  // The extra parameters' values once more by name, for a reader of the
  // file; the names alone survive a refit that failed (no fitted values).
  Json extra = Json::object();
  for (const auto& p : c.fit.parameters)
    if (std::find(c.extra_parameters.begin(), c.extra_parameters.end(), p.name) != c.extra_parameters.end())
      extra[p.name] = ParameterToJson(p);
  return {{"name", c.name},
          {"description", c.description},
          {"rig_check", c.rig_check},
          {"measurement", c.measurement},
          {"score", Number(c.signature_score)},
          {"converged", c.converged},
          {"status", c.status},
          {"significant", c.significant},
          {"extra_parameters", extra},
          {"extra_parameter_names", c.extra_parameters},
          {"residual_before", Number(residual_before)},
          {"residual_after", c.converged ? Number(c.fit.chi_square) : Json(nullptr)},
          {"residual_drop", Number(c.residual_drop)},
          {"likelihood_ratio", Number(c.likelihood_ratio)},
          {"test_dof", c.test_dof},
          {"p_value", Number(c.p_value)},
          {"seconds", Number(c.seconds)},
          {"fit", FitToJson(c.fit)}};
}

Json Phasor(std::complex<double> z) { return Json::array({Number(z.real()), Number(z.imag())}); }

Json ResponseToJson(const ResponsePoint& p) {
  return {{"level", p.level},
          {"frequency_hz", Number(p.frequency_hz)},
          {"channel", p.channel},
          {"held_out", p.held_out},
          {"measured", Phasor(p.measured)},
          {"base_model", Phasor(p.base_model)},
          {"final_model", Phasor(p.final_model)}};
}

Json SuggestionToJson(const MeasurementSuggestion& m) {
  Json positions = Json::array();
  for (const auto& p : m.positions) positions.push_back({Number(p.position_m), Number(p.expected_chi_square_difference)});
  Json levels = Json::array();
  for (const auto& l : m.levels) levels.push_back({{"level", l.level}, {"share", Number(l.share)}});
  return {{"candidates", {m.first, m.second}},
          {"best_position_m", Number(m.best.position_m)},
          {"best_expected_chi_square_difference", Number(m.best.expected_chi_square_difference)},
          {"current_expected_chi_square_difference", Number(m.current_expected)},
          {"positions", positions},
          {"levels", levels},
          {"focus_hz", {Number(m.focus_low_hz), Number(m.focus_high_hz)}},
          {"text", m.text}};
}

// ---------------------------------------------------------------- reading

using Field = JsonField;

ParameterEstimate ParameterFromJson(const Field& f, const std::string& name) {
  f.OnlyKeys({"value", "std", "unit", "ci95"});
  const Field ci = f.At("ci95");
  if (ci.Size() != 2) ci.Fail("must be [low, high]");
  return {.name = name,
          .unit = f.String("unit"),
          .value = f.Number("value"),
          .std = f.Number("std"),
          .lower_95 = ci.At(0).Number(),
          .upper_95 = ci.At(1).Number()};
}

FitSummary FitFromJson(const Field& f) {
  f.OnlyKeys({"parameters", "model_harmonics", "chi_square", "degrees_of_freedom", "num_residuals",
              "reduced_chi_square", "aic", "bic", "held_out_chi_square", "held_out_h1_relative_error",
              "held_out_num_residuals"});
  FitSummary s;
  const Field parameters = f.At("parameters").Object();
  for (const auto& [name, value] : parameters.json().items())
    s.parameters.push_back(ParameterFromJson(parameters.At(name), name));
  s.model_harmonics = f.Integer("model_harmonics");
  s.chi_square = f.Number("chi_square");
  s.degrees_of_freedom = f.Integer("degrees_of_freedom");
  s.num_residuals = f.Integer("num_residuals");
  s.reduced_chi_square = f.Number("reduced_chi_square");
  s.aic = f.Number("aic");
  s.bic = f.Number("bic");
  s.held_out_chi_square = f.Number("held_out_chi_square");
  s.held_out_h1_relative_error = f.Number("held_out_h1_relative_error");
  if (f.Has("held_out_num_residuals")) s.held_out_num_residuals = f.Integer("held_out_num_residuals");
  return s;
}

LoopEvidence LoopsFromJson(const Field& f) {
  f.OnlyKeys({"steps", "num_steps_used", "area_exponent", "area_exponent_std", "viscous_chi2", "viscous_dof",
              "viscous_p_value", "mean_equivalent_damping_Nms_rad", "damping_ratio_high_to_low",
              "elastic_harmonic_chi2", "hysteretic_harmonic_chi2", "harmonic_dof", "elastic_harmonic_p_value",
              "hysteretic_harmonic_p_value", "max_moment_harmonic_ratio", "theta_even_chi2", "theta_even_dof",
              "theta_even_p_value", "dissipation_not_viscous", "non_elliptic", "hysteretic_shape", "asymmetric"});
  LoopEvidence loops;
  const Field steps = f.At("steps");
  for (std::size_t i = 0; i < steps.Size(); ++i) {
    const Field s = steps.At(i);
    s.OnlyKeys({"level", "frequency_hz", "omega_rad_s", "theta_amplitude_rad", "theta_std_rad", "moment_amplitude_Nm",
                "dissipated_energy_J", "dissipated_energy_std_J", "viscous_energy_J", "equivalent_damping_Nms_rad",
                "equivalent_damping_std_Nms_rad", "moment_harmonic_ratio", "elastic_harmonic_chi2",
                "hysteretic_harmonic_chi2", "harmonic_dof", "theta_even_fraction", "moment_even_fraction"});
    LoopStep step;
    step.level = s.String("level");
    step.omega_rad_s =
        s.Has("omega_rad_s") ? s.Positive("omega_rad_s") : 2.0 * std::numbers::pi * s.Positive("frequency_hz");
    step.theta_amplitude_rad = s.Number("theta_amplitude_rad");
    step.theta_std_rad = s.NonNegative("theta_std_rad");
    step.moment_amplitude_Nm = s.Number("moment_amplitude_Nm");
    step.dissipated_energy_J = s.Number("dissipated_energy_J");
    step.dissipated_energy_std_J = s.NonNegative("dissipated_energy_std_J");
    step.viscous_energy_J = s.Number("viscous_energy_J");
    step.equivalent_damping_Nms_rad = s.Number("equivalent_damping_Nms_rad");
    step.equivalent_damping_std_Nms_rad = s.NonNegative("equivalent_damping_std_Nms_rad");
    step.moment_harmonic_ratio = s.Number("moment_harmonic_ratio");
    step.elastic_harmonic_chi2 = s.NonNegative("elastic_harmonic_chi2");
    step.hysteretic_harmonic_chi2 = s.NonNegative("hysteretic_harmonic_chi2");
    step.harmonic_dof = s.Integer("harmonic_dof");
    step.theta_even_fraction = s.Number("theta_even_fraction");
    step.moment_even_fraction = s.Number("moment_even_fraction");
    loops.steps.push_back(std::move(step));
  }
  loops.num_steps_used = f.Count("num_steps_used");
  loops.area_exponent = f.Number("area_exponent");
  loops.area_exponent_std = f.NonNegative("area_exponent_std");
  loops.viscous_chi2 = f.NonNegative("viscous_chi2");
  loops.viscous_dof = f.Integer("viscous_dof");
  loops.viscous_p_value = f.Probability("viscous_p_value");
  loops.mean_equivalent_damping_Nms_rad = f.Number("mean_equivalent_damping_Nms_rad");
  loops.damping_ratio_high_to_low = f.Number("damping_ratio_high_to_low");
  loops.elastic_harmonic_chi2 = f.NonNegative("elastic_harmonic_chi2");
  loops.hysteretic_harmonic_chi2 = f.NonNegative("hysteretic_harmonic_chi2");
  loops.harmonic_dof = f.Integer("harmonic_dof");
  loops.elastic_harmonic_p_value = f.Probability("elastic_harmonic_p_value");
  loops.hysteretic_harmonic_p_value = f.Probability("hysteretic_harmonic_p_value");
  loops.max_moment_harmonic_ratio = f.Number("max_moment_harmonic_ratio");
  loops.theta_even_chi2 = f.NonNegative("theta_even_chi2");
  loops.theta_even_dof = f.Integer("theta_even_dof");
  loops.theta_even_p_value = f.Probability("theta_even_p_value");
  loops.dissipation_not_viscous = f.Boolean("dissipation_not_viscous");
  loops.non_elliptic = f.Boolean("non_elliptic");
  loops.hysteretic_shape = f.Boolean("hysteretic_shape");
  loops.asymmetric = f.Boolean("asymmetric");
  return loops;
}

MisfitLocation LocationFromJson(const Field& f) {
  f.OnlyKeys({"error", "chi2", "dof", "p_value", "significant", "num_groups_tested", "in_phase_fraction",
              "near_resonance_fraction", "fundamental_fraction", "even_harmonic_fraction", "beyond_fitted_fraction",
              "harmonic_excess_chi2", "channel_excess_chi2", "level_growth_exponent", "level_misfit_amplitude",
              "level_response_amplitude", "loops", "findings", "groups"});
  MisfitLocation location;
  location.chi2 = f.NonNegative("chi2");
  location.dof = f.Integer("dof");
  location.p_value = f.Probability("p_value");
  location.significant = f.Boolean("significant");
  location.num_groups_tested = f.Count("num_groups_tested");
  const Field groups = f.At("groups");
  for (std::size_t i = 0; i < groups.Size(); ++i) {
    const Field g = groups.At(i);
    g.OnlyKeys({"channel", "harmonic", "level", "part", "band", "chi2", "dof", "p_value", "adjusted_p_value",
                "significant", "excess_chi2", "growth_exponent"});
    location.groups.push_back({.channel = g.String("channel"),
                               .harmonic = g.Integer("harmonic"),
                               .level = g.String("level"),
                               .part = g.String("part"),
                               .band = g.String("band"),
                               .chi2 = g.NonNegative("chi2"),
                               .dof = g.Integer("dof"),
                               .p_value = g.Probability("p_value"),
                               .adjusted_p_value = g.Probability("adjusted_p_value"),
                               .significant = g.Boolean("significant"),
                               .excess_chi2 = g.Number("excess_chi2"),
                               .growth_exponent = g.Number("growth_exponent")});
  }
  location.in_phase_fraction = f.Number("in_phase_fraction");
  location.near_resonance_fraction = f.Number("near_resonance_fraction");
  location.fundamental_fraction = f.Number("fundamental_fraction");
  location.even_harmonic_fraction = f.Number("even_harmonic_fraction");
  location.beyond_fitted_fraction = f.Number("beyond_fitted_fraction");
  location.harmonic_excess_chi2 = f.At("harmonic_excess_chi2").Numbers();
  location.channel_excess_chi2 = f.At("channel_excess_chi2").Numbers();
  location.level_growth_exponent = f.Number("level_growth_exponent");
  location.level_misfit_amplitude = f.At("level_misfit_amplitude").Numbers();
  location.level_response_amplitude = f.At("level_response_amplitude").Numbers();
  location.loops = LoopsFromJson(f.At("loops"));
  location.findings = f.At("findings").Strings();
  return location;
}

CandidateOutcome CandidateFromJson(const Field& f) {
  f.OnlyKeys({"name", "description", "rig_check", "measurement", "score", "converged", "status", "significant", "extra_parameters",
              "extra_parameter_names", "residual_before", "residual_after", "residual_drop", "likelihood_ratio",
              "test_dof", "p_value", "seconds", "fit"});
  CandidateOutcome c;
  c.name = f.String("name");
  c.description = f.String("description");
  if (f.Has("rig_check")) c.rig_check = f.String("rig_check");
  if (f.Has("measurement")) c.measurement = f.Boolean("measurement");
  c.signature_score = f.Number("score");
  c.converged = f.Boolean("converged");
  c.status = f.String("status");
  c.significant = f.Boolean("significant");
  const Field extra = f.At("extra_parameters").Object();
  if (f.Has("extra_parameter_names")) {
    c.extra_parameters = f.At("extra_parameter_names").Strings();
  } else {
    for (const auto& [name, value] : extra.json().items()) c.extra_parameters.push_back(name);
  }
  c.residual_drop = f.Number("residual_drop");
  c.likelihood_ratio = f.Number("likelihood_ratio");
  c.test_dof = f.Integer("test_dof");
  c.p_value = f.Probability("p_value");
  c.seconds = f.NonNegative("seconds");
  c.fit = FitFromJson(f.At("fit"));
  return c;
}

ResponsePoint ResponseFromJson(const Field& f) {
  f.OnlyKeys({"level", "frequency_hz", "channel", "held_out", "measured", "base_model", "final_model"});
  return {.level = f.String("level"),
          .frequency_hz = f.Positive("frequency_hz"),
          .channel = f.String("channel"),
          .held_out = f.Boolean("held_out"),
          .measured = f.At("measured").Phasor(),
          .base_model = f.At("base_model").Phasor(),
          .final_model = f.At("final_model").Phasor()};
}

MeasurementSuggestion SuggestionFromJson(const Field& f) {
  f.OnlyKeys({"candidates", "best_position_m", "best_expected_chi_square_difference",
              "current_expected_chi_square_difference", "positions", "levels", "focus_hz", "text"});
  MeasurementSuggestion m;
  const std::vector<std::string> names = f.At("candidates").Strings();
  if (names.size() != 2) f.At("candidates").Fail("must name the two candidates");
  m.first = names[0];
  m.second = names[1];
  m.best = {.position_m = f.Number("best_position_m"),
            .expected_chi_square_difference = f.Number("best_expected_chi_square_difference")};
  m.current_expected = f.Number("current_expected_chi_square_difference");
  const Field positions = f.At("positions");
  for (std::size_t i = 0; i < positions.Size(); ++i) {
    const std::vector<double> p = positions.At(i).Numbers();
    if (p.size() != 2) positions.At(i).Fail("must be [position_m, expected chi-square difference]");
    m.positions.push_back({.position_m = p[0], .expected_chi_square_difference = p[1]});
  }
  const Field levels = f.At("levels");
  for (std::size_t i = 0; i < levels.Size(); ++i)
    m.levels.push_back({.level = levels.At(i).String("level"), .share = levels.At(i).Number("share")});
  const std::vector<double> focus = f.At("focus_hz").Numbers();
  if (focus.size() != 2) f.At("focus_hz").Fail("must be [low, high]");
  m.focus_low_hz = focus[0];
  m.focus_high_hz = focus[1];
  m.text = f.String("text");
  return m;
}

DiagnosisResult ResultFromJson(const Field& root) {
  root.OnlyKeys({"format", "beamid_version", "campaign", "campaign_sha256", "result", "result_file", "selected", "verdict", "ranked_by",
                 "rest_within_noise", "blame", "recording_findings", "suggestion", "combinations", "summary", "base", "final", "candidates", "location", "response", "seconds"});
  DiagnosisResult r;
  r.selected = root.At("selected").Strings();
  r.verdict = root.String("verdict");
  if (root.Has("ranked_by")) r.ranked_by = root.String("ranked_by");
  if (root.Has("rest_within_noise")) r.rest_within_noise = root.Boolean("rest_within_noise");
  if (root.Has("blame")) r.blame = root.String("blame");
  if (root.Has("recording_findings")) r.recording_findings = root.At("recording_findings").Strings();
  if (root.Has("suggestion")) r.suggestion = SuggestionFromJson(root.At("suggestion"));
  if (root.Has("combinations")) {
    const Field combinations = root.At("combinations");
    for (std::size_t i = 0; i < combinations.Size(); ++i)
      r.combinations.push_back(CandidateFromJson(combinations.At(i)));
  }
  r.summary = root.String("summary");
  r.base = FitFromJson(root.At("base"));
  const Field candidates = root.At("candidates");
  for (std::size_t i = 0; i < candidates.Size(); ++i) r.candidates.push_back(CandidateFromJson(candidates.At(i)));
  const Field final_model = root.At("final");
  final_model.OnlyKeys({"extension", "fit", "extra_parameter_names"});
  r.final_fit = FitFromJson(final_model.At("fit"));
  if (final_model.Has("extra_parameter_names")) {
    r.final_extra_parameters = final_model.At("extra_parameter_names").Strings();
  } else if (!r.selected.empty()) {
    // Older files: the selected candidate's.
    for (const auto& c : r.candidates)
      if (c.name == r.selected.front()) r.final_extra_parameters = c.extra_parameters;
  }
  const Field location = root.At("location").Object();
  if (location.Has("error")) r.location_error = location.String("error");
  // {"error": ...} alone: locating failed.
  bool located = false;
  for (const auto& item : location.json().items()) located = located || item.key() != "error";
  if (located) r.location = LocationFromJson(location);
  if (root.Has("response")) {
    const Field response = root.At("response");
    for (std::size_t i = 0; i < response.Size(); ++i) r.response.push_back(ResponseFromJson(response.At(i)));
  }
  r.seconds = root.NonNegative("seconds");
  return r;
}

}  // namespace

std::string DiagnosisFileToJson(const DiagnosisFile& file) {
  const DiagnosisResult& r = file.diagnosis;
  Json root = Json::object();
  root["format"] = std::string(kDiagnosisFormat);
  root["beamid_version"] = file.beamid_version;
  root["campaign"] = {{"folder", file.campaign_folder}, {"name", file.campaign_name}};
  if (!file.campaign_sha256.empty()) root["campaign_sha256"] = file.campaign_sha256;
  if (!file.result_file.empty()) root["result_file"] = file.result_file;
  if (!file.embedded_result_json.empty()) {
    root["result"] = ParseStrictJson<Json>(file.embedded_result_json, "DiagnosisFile::embedded_result_json", "");
  }
  root["selected"] = r.selected;
  root["verdict"] = r.verdict;
  root["ranked_by"] = r.ranked_by;
  root["rest_within_noise"] = r.rest_within_noise;
  root["blame"] = r.blame;
  root["recording_findings"] = r.recording_findings;
  if (r.suggestion) root["suggestion"] = SuggestionToJson(*r.suggestion);
  if (!r.combinations.empty()) {
    // Each pair's residual_before is the first cause's (what it is tested against).
    const double before = r.candidates.empty() ? r.base.chi_square : r.candidates.front().fit.chi_square;
    Json combinations = Json::array();
    for (const auto& c : r.combinations) combinations.push_back(CandidateToJson(c, before));
    root["combinations"] = combinations;
  }
  root["summary"] = r.summary;
  root["base"] = FitToJson(r.base);
  root["final"] = {{"extension", r.selected},
                   {"fit", FitToJson(r.final_fit)},
                   {"extra_parameter_names", r.final_extra_parameters}};
  Json candidates = Json::array();
  for (const auto& c : r.candidates) candidates.push_back(CandidateToJson(c, r.base.chi_square));
  root["candidates"] = candidates;
  Json location = r.location ? LocationToJson(*r.location) : Json::object();
  if (!r.location || !r.location_error.empty()) location["error"] = r.location_error;
  root["location"] = location;
  Json response = Json::array();
  for (const auto& p : r.response) response.push_back(ResponseToJson(p));
  root["response"] = response;
  root["seconds"] = Number(r.seconds);
  return root.dump(1) + "\n";
}

DiagnosisFile DiagnosisFileFromJson(const std::string& text, const std::string& source) {
  const Json json = ParseJsonObject(text, source, "diagnosis", "give a diagnosis.json written by 'beamid diagnose'");
  const Field root(json, "", source, kDiagnosisFormat, kFix);
  const std::string format = root.String("format");
  if (format != kDiagnosisFormat)
    throw InputError(source + ": field \"format\" is \"" + format + "\", not \"" + std::string(kDiagnosisFormat) +
                     "\". Fix: give a diagnosis.json written by 'beamid diagnose' (a result.json of 'beamid "
                     "identify' is format beamid-result/1)");
  DiagnosisFile file;
  file.beamid_version = root.Has("beamid_version") ? root.String("beamid_version") : "";
  if (root.Has("campaign")) {
    const Field campaign = root.At("campaign");
    campaign.OnlyKeys({"folder", "name"});
    file.campaign_folder = campaign.String("folder");
    file.campaign_name = campaign.String("name");
  }
  if (root.Has("campaign_sha256")) file.campaign_sha256 = root.String("campaign_sha256");
  if (root.Has("result")) {
    const Field result = root.At("result");
    if (result.json().is_string()) file.result_file = result.String();
    else if (result.json().is_object()) file.embedded_result_json = result.json().dump();
    else result.Fail("must be the result.json's path or its object, not a " + std::string(result.json().type_name()));
  }
  if (file.result_file.empty() && root.Has("result_file")) file.result_file = root.String("result_file");
  file.diagnosis = ResultFromJson(root);
  return file;
}

void WriteDiagnosisFile(const std::filesystem::path& path, const DiagnosisFile& file) {
  WriteTextFileAtomically(path, DiagnosisFileToJson(file));
}

DiagnosisFile ReadDiagnosisFile(const std::filesystem::path& path) {
  return DiagnosisFileFromJson(
      ReadTextFile(path, "diagnosis file", "give the diagnosis.json written by 'beamid diagnose'"), path.string());
}

std::string CandidateRefitToText(const CandidateRefit& refit) {
  const nlohmann::json j = {{"chi_square", ExactJsonNumber(refit.chi_square)},
                            {"seconds", ExactJsonNumber(refit.seconds)},
                            {"values", ExactJsonNumbers(refit.values)},
                            {"std", ExactJsonNumbers(refit.std)},
                            {"scaled_at", ExactJsonNumbers(refit.scaled_at)},
                            {"x", ExactJsonNumbers(refit.x)},
                            {"artefact_value", ExactJsonNumber(refit.artefact_value)},
                            {"artefact_std", ExactJsonNumber(refit.artefact_std)}};
  return j.dump();
}

CandidateRefit CandidateRefitFromText(const std::string& text) {
  try {
    const nlohmann::json j = ParseStrictJson<nlohmann::json>(text, "a candidate refit's record", "");
    return {.chi_square = ExactNumberFromJson(j.at("chi_square")),
            .seconds = ExactNumberFromJson(j.at("seconds")),
            .values = ExactNumbersFromJson(j.at("values")),
            .std = ExactNumbersFromJson(j.at("std")),
            .scaled_at = ExactNumbersFromJson(j.at("scaled_at")),
            .x = ExactNumbersFromJson(j.at("x")),
            .artefact_value = ExactNumberFromJson(j.at("artefact_value")),
            .artefact_std = ExactNumberFromJson(j.at("artefact_std"))};
  } catch (const std::exception& e) {
    throw std::runtime_error(std::string("a candidate refit's record is damaged: ") + e.what());
  }
}

}  // namespace beamid::solver
