#include "solver/diagnosis/diagnosis_io.h"

#include <algorithm>
#include <cstdint>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <type_traits>

#include <nlohmann/json.hpp>

#include "hb/errors.h"
#include "hb/json_field.h"
#include "hb/json_schema.h"
#include "hb/option_checks.h"
#include "hb/text_file.h"
#include "solver/estimation/damping_laws_schema.h"

namespace beamid::solver {
namespace {

using schema::Column;
using schema::Count;
using schema::kOptional;
using schema::kOmittedWhenEmpty;
using schema::Limits;
using schema::Presence;
using schema::TextRule;

constexpr schema::Format kDiagnosisSchema{kDiagnosisFormat, "diagnosis",
                                          "give a diagnosis.json written by 'beamid diagnose', or repair that field"};

// Bounds on what a file can make the reader hold, far above what one
// diagnosis writes.
constexpr int kMaxCandidates = 1'000;
constexpr int kMaxParameters = 1'000;
constexpr int kMaxFindings = 10'000;
constexpr int kMaxEntries = 1'000'000;  // steps, groups, response points, levels, channels
constexpr std::int64_t kMaxCount = 1'000'000'000;  // residuals, degrees of freedom
constexpr int kMaxModelHarmonics = 2 * option_checks::kMaxHarmonics + 1;  // harmonic_truncation's 2H + 1

// A statistic that is NaN when it has nothing to measure (a held-out χ²
// without held-out channels), which the file holds as null.
constexpr Limits NonNegativeOrNull() { return schema::NonNegative().OrNull(); }
constexpr Limits AnyOrNull() { return schema::Any().OrNull(); }

// A parameter's estimate, keyed by its name. Declared here, not by lookup:
// the result file declares ParameterEstimate in its own way.
const auto kParameter = [](auto& io, auto& p) {
  io.Number("value", p.value, "as \"unit\"", AnyOrNull());
  io.Number("std", p.std, "as \"unit\"", NonNegativeOrNull());
  io.Text("unit", p.unit);
  static constexpr Column<ParameterEstimate> kCi95[] = {
      {&ParameterEstimate::lower_95, "low", "as \"unit\"", AnyOrNull()},
      {&ParameterEstimate::upper_95, "high", "as \"unit\"", AnyOrNull()}};
  io.Row("ci95", p, kCi95);
};

// A candidate as the file holds it: beside its outcome, the χ² it was
// tested against and its extra parameters' estimates by name (written for
// a reader of the file; older files name the extra parameters only there).
struct CandidateEntry {
  CandidateOutcome outcome;
  double residual_before = 0.0;
  std::vector<ParameterEstimate> extra;
  // Files older than "refit" said "status": "solved", "failed: …" or "not
  // refitted: …" (never written now).
  std::string older_status;
};

void Describe(auto& io, schema::Like<CandidateEntry> auto& e) {
  auto& c = e.outcome;
  io.Text("name", c.name, TextRule::kNotEmpty);
  io.Text("description", c.description);
  io.Text("rig_check", c.rig_check, TextRule::kAny, kOptional);
  io.Boolean("measurement", c.measurement, kOptional);
  io.Number("score", c.signature_score, "1", schema::Probability());
  io.Choice("refit", c.status, kRefitStatusNames, kOptional);
  io.Text("refit_message", c.status_message, TextRule::kAny, kOmittedWhenEmpty);
  io.Ignored("converged");  // older files; "refit" or "status" tells it
  io.Text("status", e.older_status, TextRule::kAny, kOmittedWhenEmpty);
  io.Boolean("significant", c.significant);
  io.Keyed("extra_parameters", e.extra, &ParameterEstimate::name, kMaxParameters, Presence::kRequired, kParameter);
  io.Texts("extra_parameter_names", c.extra_parameters, kMaxParameters, TextRule::kNotEmpty, kOptional);
  io.Derived("residual_before", e.residual_before, "1");
  io.Derived("residual_after", c.Refitted() ? c.fit.chi_square : std::numeric_limits<double>::quiet_NaN(), "1");
  io.Number("residual_drop", c.residual_drop, "1", NonNegativeOrNull());
  io.Number("likelihood_ratio", c.likelihood_ratio, "1", AnyOrNull());
  io.Integer("test_dof", c.test_dof, 0, kMaxParameters);
  io.Number("p_value", c.p_value, "1", schema::Probability().OrNull());
  io.Number("seconds", c.seconds, "s", schema::NonNegative());
  io.Object("fit", c.fit);
}

CandidateEntry Entry(const CandidateOutcome& c, double residual_before) {
  CandidateEntry e{.outcome = c, .residual_before = residual_before};
  for (const ParameterEstimate& p : c.fit.parameters)
    if (std::find(c.extra_parameters.begin(), c.extra_parameters.end(), p.name) != c.extra_parameters.end())
      e.extra.push_back(p);
  return e;
}

CandidateOutcome Outcome(CandidateEntry e) {
  if (!e.older_status.empty()) {
    const auto after = [&](std::string_view prefix) {
      return e.older_status.starts_with(prefix) ? e.older_status.substr(prefix.size()) : e.older_status;
    };
    e.outcome.status = e.older_status == "solved"                  ? RefitStatus::kRefitted
                       : e.older_status.starts_with("not refitted") ? RefitStatus::kNotRefitted
                                                                   : RefitStatus::kFailed;
    if (e.outcome.status == RefitStatus::kNotRefitted) e.outcome.status_message = after("not refitted: ");
    if (e.outcome.status == RefitStatus::kFailed && e.older_status != "failed")
      e.outcome.status_message = after("failed: ");
  }
  // Older files: the names only as the keys of extra_parameters (which
  // holds no more than the names, so it is empty when they are).
  if (e.outcome.extra_parameters.empty())
    for (const ParameterEstimate& p : e.extra) e.outcome.extra_parameters.push_back(p.name);
  return std::move(e.outcome);
}

// The whole file: a DiagnosisFile and the fields it holds only as the
// file has them.
struct DiagnosisRecord {
  DiagnosisFile file{.beamid_version = ""};  // "" in files older than the key
  // "result": the embedded result.json (or, in older files, its path) as JSON text.
  std::string result;
  std::vector<CandidateEntry> candidates;
  std::vector<CandidateEntry> combinations;
  std::vector<std::string> final_extension;  // = the selected
};

void Describe(auto& io, schema::Like<DiagnosisRecord> auto& rec) {
  auto& file = rec.file;
  auto& r = file.diagnosis;
  io.Constant("format", kDiagnosisFormat);
  io.Text("beamid_version", file.beamid_version, TextRule::kAny, kOptional);
  io.Object("campaign", file, kOptional, [](auto& campaign_io, auto& f) {
    campaign_io.Text("folder", f.campaign_folder);
    campaign_io.Text("name", f.campaign_name);
  });
  io.Text("campaign_sha256", file.campaign_sha256, TextRule::kAny, kOmittedWhenEmpty);
  io.Choice("phasor_uncertainty", file.phasor_uncertainty, kPhasorUncertaintyNames, kOptional);
  io.Text("result_file", file.result_file, TextRule::kNotEmpty, kOmittedWhenEmpty);
  io.Verbatim("result", rec.result, kOmittedWhenEmpty);
  const std::size_t first = rec.result.find_first_not_of(" \t\r\n");
  io.Check(first == std::string::npos || rec.result[first] == '{' || rec.result[first] == '"',
           "\"result\" is the result.json's path or its object", "result");
  io.Texts("selected", r.selected, kMaxCandidates, TextRule::kNotEmpty);
  io.Choice("verdict", r.verdict, kDiagnosisVerdictNames);
  io.Choice("ranked_by", r.ranked_by, kRankedByNames, kOptional);
  io.Boolean("rest_within_noise", r.rest_within_noise, kOptional);
  io.Choice("blame", r.blame, kBlameNames, kOptional);
  io.Texts("recording_findings", r.recording_findings, kMaxFindings, TextRule::kAny, kOptional);
  io.Object("suggestion", r.suggestion, kOmittedWhenEmpty);
  io.List("combinations", rec.combinations, kMaxCandidates, kOmittedWhenEmpty);
  io.Text("summary", r.summary);
  io.Object("base", r.base);
  io.Object("final", rec, Presence::kRequired, [](auto& final_io, auto& x) {
    final_io.Texts("extension", x.final_extension, kMaxCandidates, TextRule::kNotEmpty);
    final_io.Object("fit", x.file.diagnosis.final_fit);
    final_io.Texts("extra_parameter_names", x.file.diagnosis.final_extra_parameters, kMaxParameters,
                   TextRule::kNotEmpty, kOptional);
    final_io.Object("damping_laws", x.file.diagnosis.final_damping_laws, kOmittedWhenEmpty,
                    damping_laws_schema::kEnvelope);
    final_io.Object("backbone", x.file.diagnosis.final_backbone, kOmittedWhenEmpty);
  });
  io.Check(rec.final_extension == r.selected, "final.extension names the selected candidates", "final.extension");
  io.List("candidates", rec.candidates, kMaxCandidates);
  // The location's fields, or {"error": why locating failed}.
  io.Object("location", r, Presence::kRequired, [](auto& location_io, auto& x) {
    location_io.Inline(x.location);
    location_io.Text("error", x.location_error, TextRule::kAny, kOmittedWhenEmpty);
  });
  io.List("response", r.response, kMaxEntries, kOptional);
  io.Number("seconds", r.seconds, "s", schema::NonNegative());
}

}  // namespace

// The declarations of the structs the file holds (hb/json_schema.h): its
// writer, reader and documentation.

void Describe(auto& io, schema::Like<FitSummary> auto& s) {
  io.Keyed("parameters", s.parameters, &ParameterEstimate::name, kMaxParameters, Presence::kRequired, kParameter);
  io.Integer("model_harmonics", s.model_harmonics, 1, kMaxModelHarmonics);
  io.Number("chi_square", s.chi_square, "1", NonNegativeOrNull());
  io.Integer("degrees_of_freedom", s.degrees_of_freedom, 0, kMaxCount);
  io.Integer("num_residuals", s.num_residuals, 0, kMaxCount);
  io.Number("reduced_chi_square", s.reduced_chi_square, "1", NonNegativeOrNull());
  io.Number("aic", s.aic, "1", NonNegativeOrNull());
  io.Number("bic", s.bic, "1", NonNegativeOrNull());
  io.Number("held_out_chi_square", s.held_out_chi_square, "1", NonNegativeOrNull());
  io.Number("held_out_h1_relative_error", s.held_out_h1_relative_error, "1", NonNegativeOrNull());
  io.Integer("held_out_num_residuals", s.held_out_num_residuals, 0, kMaxCount, kOptional);
}

void Describe(auto& io, schema::Like<LoopStep> auto& s) {
  io.Text("level", s.level);
  // Written for a reader of the file; older files have it alone.
  double frequency_hz = s.omega_rad_s / (2.0 * std::numbers::pi);
  io.Number("frequency_hz", frequency_hz, "Hz", schema::Positive());
  // Exact: frequency_hz·2π need not give it back.
  io.Number("omega_rad_s", s.omega_rad_s, "rad/s", schema::Positive(), kOptional);
  if constexpr (std::remove_cvref_t<decltype(io)>::kReading)
    if (s.omega_rad_s == 0.0) s.omega_rad_s = 2.0 * std::numbers::pi * frequency_hz;
  io.Number("theta_amplitude_rad", s.theta_amplitude_rad, "rad", schema::NonNegative());
  io.Number("theta_std_rad", s.theta_std_rad, "rad", NonNegativeOrNull());
  io.Number("moment_amplitude_Nm", s.moment_amplitude_Nm, "N m", schema::NonNegative());
  io.Number("dissipated_energy_J", s.dissipated_energy_J, "J", AnyOrNull());
  io.Number("dissipated_energy_std_J", s.dissipated_energy_std_J, "J", NonNegativeOrNull());
  io.Number("viscous_energy_J", s.viscous_energy_J, "J", AnyOrNull());
  io.Number("equivalent_damping_Nms_rad", s.equivalent_damping_Nms_rad, "N m s/rad", AnyOrNull());
  io.Number("equivalent_damping_std_Nms_rad", s.equivalent_damping_std_Nms_rad, "N m s/rad", NonNegativeOrNull());
  io.Number("moment_harmonic_ratio", s.moment_harmonic_ratio, "1", NonNegativeOrNull());
  io.Number("elastic_harmonic_chi2", s.elastic_harmonic_chi2, "1", NonNegativeOrNull());
  io.Number("hysteretic_harmonic_chi2", s.hysteretic_harmonic_chi2, "1", NonNegativeOrNull());
  io.Integer("harmonic_dof", s.harmonic_dof, 0, kMaxCount);
  io.Number("theta_even_fraction", s.theta_even_fraction, "1", schema::Probability().OrNull());
  io.Number("moment_even_fraction", s.moment_even_fraction, "1", schema::Probability().OrNull());
}

void Describe(auto& io, schema::Like<LoopEvidence> auto& l) {
  io.List("steps", l.steps, kMaxEntries);
  io.Integer("num_steps_used", l.num_steps_used, 0, kMaxEntries);
  io.Number("area_exponent", l.area_exponent, "1", AnyOrNull());
  io.Number("area_exponent_std", l.area_exponent_std, "1", NonNegativeOrNull());
  io.Number("viscous_chi2", l.viscous_chi2, "1", NonNegativeOrNull());
  io.Integer("viscous_dof", l.viscous_dof, 0, kMaxCount);
  io.Number("viscous_p_value", l.viscous_p_value, "1", schema::Probability().OrNull());
  io.Number("mean_equivalent_damping_Nms_rad", l.mean_equivalent_damping_Nms_rad, "N m s/rad", AnyOrNull());
  io.Number("damping_ratio_high_to_low", l.damping_ratio_high_to_low, "1", AnyOrNull());
  io.Number("elastic_harmonic_chi2", l.elastic_harmonic_chi2, "1", NonNegativeOrNull());
  io.Number("hysteretic_harmonic_chi2", l.hysteretic_harmonic_chi2, "1", NonNegativeOrNull());
  io.Integer("harmonic_dof", l.harmonic_dof, 0, kMaxCount);
  io.Number("elastic_harmonic_p_value", l.elastic_harmonic_p_value, "1", schema::Probability().OrNull());
  io.Number("hysteretic_harmonic_p_value", l.hysteretic_harmonic_p_value, "1", schema::Probability().OrNull());
  io.Number("max_moment_harmonic_ratio", l.max_moment_harmonic_ratio, "1", NonNegativeOrNull());
  io.Number("theta_even_chi2", l.theta_even_chi2, "1", NonNegativeOrNull());
  io.Integer("theta_even_dof", l.theta_even_dof, 0, kMaxCount);
  io.Number("theta_even_p_value", l.theta_even_p_value, "1", schema::Probability().OrNull());
  io.Boolean("dissipation_not_viscous", l.dissipation_not_viscous);
  io.Boolean("non_elliptic", l.non_elliptic);
  io.Boolean("hysteretic_shape", l.hysteretic_shape);
  io.Boolean("asymmetric", l.asymmetric);
}

void Describe(auto& io, schema::Like<MisfitGroupTest> auto& g) {
  io.Text("channel", g.channel);  // "" = all channels
  io.Integer("harmonic", g.harmonic, 0, kMaxModelHarmonics);  // 0 = all harmonics
  io.Text("level", g.level);      // "" = all levels
  io.Choice("part", g.part, kResidualPartNames);
  io.Choice("band", g.band, kFrequencyBandNames);
  io.Number("chi2", g.chi2, "1", schema::NonNegative());
  io.Integer("dof", g.dof, 0, kMaxCount);
  io.Number("p_value", g.p_value, "1", schema::Probability());
  io.Number("adjusted_p_value", g.adjusted_p_value, "1", schema::Probability());
  io.Boolean("significant", g.significant);
  io.Number("excess_chi2", g.excess_chi2, "1", schema::NonNegative());
  io.Number("growth_exponent", g.growth_exponent, "1", AnyOrNull());
}

void Describe(auto& io, schema::Like<MisfitLocation> auto& m) {
  io.Number("chi2", m.chi2, "1", schema::NonNegative());
  io.Integer("dof", m.dof, 0, kMaxCount);
  io.Number("p_value", m.p_value, "1", schema::Probability());
  io.Boolean("significant", m.significant);
  io.Integer("num_groups_tested", m.num_groups_tested, 0, kMaxEntries);
  io.Number("in_phase_fraction", m.in_phase_fraction, "1", schema::Probability());
  io.Number("near_resonance_fraction", m.near_resonance_fraction, "1", schema::Probability());
  io.Number("fundamental_fraction", m.fundamental_fraction, "1", schema::Probability());
  io.Number("even_harmonic_fraction", m.even_harmonic_fraction, "1", schema::Probability());
  io.Number("beyond_fitted_fraction", m.beyond_fitted_fraction, "1", schema::Probability());
  // Files older than the test of the measured even harmonics lack both.
  io.Number("measured_even_harmonics_p_value", m.measured_even_harmonics_p_value, "1", schema::Probability(), kOptional);
  io.Boolean("measured_even_harmonics", m.measured_even_harmonics, kOptional);
  io.Numbers("harmonic_excess_chi2", m.harmonic_excess_chi2, "1", NonNegativeOrNull(), kMaxModelHarmonics);
  io.Numbers("channel_excess_chi2", m.channel_excess_chi2, "1", NonNegativeOrNull(), kMaxEntries);
  io.Number("level_growth_exponent", m.level_growth_exponent, "1", AnyOrNull());
  io.Numbers("level_misfit_amplitude", m.level_misfit_amplitude, "1", NonNegativeOrNull(), kMaxEntries);
  io.Numbers("level_response_amplitude", m.level_response_amplitude, "1", NonNegativeOrNull(), kMaxEntries);
  io.Object("loops", m.loops);
  io.Texts("findings", m.findings, kMaxFindings);
  io.List("groups", m.groups, kMaxEntries);
}

void Describe(auto& io, schema::Like<ResponsePoint> auto& p) {
  io.Text("level", p.level, TextRule::kNotEmpty);
  io.Number("frequency_hz", p.frequency_hz, "Hz", schema::Positive());
  io.Text("channel", p.channel, TextRule::kNotEmpty);
  io.Boolean("held_out", p.held_out);
  io.Phasor("measured", p.measured, "SI, the channel's");
  io.Phasor("base_model", p.base_model, "SI, the channel's");
  io.Phasor("final_model", p.final_model, "SI, the channel's");
  io.Numbers("base_misfit_sigma", p.base_misfit_sigma, "σ (per harmonic 1..K)", NonNegativeOrNull(),
             kMaxModelHarmonics, kOmittedWhenEmpty);
  io.Numbers("final_misfit_sigma", p.final_misfit_sigma, "σ (per harmonic 1..K)", NonNegativeOrNull(),
             kMaxModelHarmonics, kOmittedWhenEmpty);
}

void Describe(auto& io, schema::Like<SensorBackbonePoint> auto& p) {
  io.Number("amplitude_m", p.amplitude_m, "m", schema::NonNegative());
  io.Number("frequency_hz", p.frequency_hz, "Hz", schema::Positive());
}

void Describe(auto& io, schema::Like<SelectedBackbone> auto& b) {
  io.Text("channel", b.channel, TextRule::kNotEmpty);
  io.Number("position_m", b.position_m, "m", schema::NonNegative());
  io.List("points", b.points, kMaxEntries, kOmittedWhenEmpty);
  io.Text("error", b.error, TextRule::kAny, kOmittedWhenEmpty);
}

void Describe(auto& io, schema::Like<LevelShare> auto& l) {
  io.Text("level", l.level, TextRule::kNotEmpty);
  io.Number("share", l.share, "1", schema::Probability());
}

void Describe(auto& io, schema::Like<MeasurementSuggestion> auto& m) {
  // The two candidates, as a pair of texts.
  std::vector<std::string> names{m.first, m.second};
  io.Texts("candidates", names, Count::Exactly(2, "2"), TextRule::kNotEmpty);
  if constexpr (std::remove_cvref_t<decltype(io)>::kReading) {
    m.first = names[0];
    m.second = names[1];
  }
  io.Number("best_position_m", m.best.position_m, "m", schema::NonNegative());
  io.Number("best_expected_chi_square_difference", m.best.expected_chi_square_difference, "1",
            schema::NonNegative());
  io.Number("current_expected_chi_square_difference", m.current_expected, "1", schema::NonNegative());
  static constexpr Column<PositionGain> kPosition[] = {
      {&PositionGain::position_m, "position_m", "m", schema::NonNegative()},
      {&PositionGain::expected_chi_square_difference, "expected chi-square difference", "1", schema::NonNegative()}};
  io.Rows("positions", m.positions, kPosition, kMaxEntries);
  io.List("levels", m.levels, kMaxEntries);
  static constexpr Column<MeasurementSuggestion> kFocus[] = {
      {&MeasurementSuggestion::focus_low_hz, "low", "Hz", schema::Positive()},
      {&MeasurementSuggestion::focus_high_hz, "high", "Hz", schema::Positive()}};
  io.Row("focus_hz", m, kFocus);
  io.Check(!(m.focus_low_hz > m.focus_high_hz), "focus_hz is [low, high], low ≤ high", "focus_hz");
  io.Text("text", m.text, TextRule::kNotEmpty);
}

std::vector<schema::FieldDoc> DiagnosisFileFields() { return schema::Fields<DiagnosisRecord>(); }

std::string DiagnosisFileToJson(const DiagnosisFile& file) {
  const DiagnosisResult& r = file.diagnosis;
  DiagnosisRecord rec{.file = file, .result = file.embedded_result_json, .final_extension = r.selected};
  for (const CandidateOutcome& c : r.candidates) rec.candidates.push_back(Entry(c, r.base.chi_square));
  // Each pair's residual_before is the first cause's (what it is tested against).
  const double before = r.candidates.empty() ? r.base.chi_square : r.candidates.front().fit.chi_square;
  for (const CandidateOutcome& c : r.combinations) rec.combinations.push_back(Entry(c, before));
  return schema::ToJson(rec);
}

DiagnosisFile DiagnosisFileFromJson(const std::string& text, const std::string& source) {
  DiagnosisRecord rec = schema::FromJson<DiagnosisRecord>(text, source, kDiagnosisSchema);
  DiagnosisFile file = std::move(rec.file);
  DiagnosisResult& r = file.diagnosis;
  if (!rec.result.empty()) {
    // Older files name the result's path by "result".
    const nlohmann::json result = nlohmann::json::parse(rec.result);
    if (result.is_string()) file.result_file = result.get<std::string>();
    else file.embedded_result_json = rec.result;
  }
  for (CandidateEntry& e : rec.candidates) r.candidates.push_back(Outcome(std::move(e)));
  for (CandidateEntry& e : rec.combinations) r.combinations.push_back(Outcome(std::move(e)));
  if (!r.final_damping_laws.empty()) JudgeDampingLaws(&r.final_damping_laws);
  if (r.final_extra_parameters.empty() && !r.selected.empty())
    // Older files: the selected candidate's.
    for (const CandidateOutcome& c : r.candidates)
      if (c.name == r.selected.front()) r.final_extra_parameters = c.extra_parameters;
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
