#include "solver/report/report_outcome.h"

#include <algorithm>
#include <cmath>

#include "hb/enum_names.h"
#include "solver/estimation/damping_laws.h"

namespace beamid::solver {
namespace {

// An enumeration's name as the files give it; null for the value they
// leave unnamed ("": not judged, no one to blame).
template <typename E, std::size_t N>
nlohmann::json NameOrNull(E value, const schema::Name<E> (&names)[N]) {
  const std::string_view name = schema::NameOf(value, names);
  return name.empty() ? nlohmann::json(nullptr) : nlohmann::json(std::string(name));
}

// NaN is null in JSON; nlohmann writes it so, and says it here for the reader.
nlohmann::json NumberOrNull(double value) {
  return std::isfinite(value) ? nlohmann::json(value) : nlohmann::json(nullptr);
}

}  // namespace

IdentificationOutcome OutcomeOf(const ReportInput& input, const ReportCurves& curves) {
  const ResultFile& result = input.result;
  IdentificationOutcome o{.model_kind = result.model.kind,
                          .support_law = result.model.law,
                          .fit_within_noise = result.fit.verdict.within_noise,
                          .chi_square = result.fit.chi_square,
                          .degrees_of_freedom = result.fit.degrees_of_freedom,
                          .reduced_chi_square = result.fit.reduced_chi_square,
                          .damping_trend = curves.measured_mode.damping.empty()
                                               ? Trend::kNotJudged
                                               : curves.measured_mode.damping_rate_trend,
                          .damping_trend_z = curves.measured_mode.damping_rate_trend_z};
  if (!result.damping_laws.laws.empty()) o.assumed_damping_law = result.damping_laws.laws.front().law;
  if (const DampingLawFit* answer = AnswerLaw(result.damping_laws)) {
    o.answer_damping_law = answer->law;
    o.answer_reduced_chi_square = answer->reduced_chi_square;
    o.assumed_damping_law_rejected = answer != &result.damping_laws.laws.front();
  }
  if (input.diagnosis) {
    const DiagnosisResult& d = input.diagnosis->diagnosis;
    o.diagnosis = DiagnosisOutcome{.verdict = d.verdict,
                                   .blame = d.blame,
                                   .ranked_by = d.ranked_by,
                                   .selected = d.selected,
                                   .rest_within_noise = d.rest_within_noise};
  }
  for (const auto& v : result.validation)
    o.held_out.push_back({.channel = v.channel,
                          .steps = static_cast<int>(v.steps.size()),
                          .worst_h1_relative_error = v.worst_h1_relative_error,
                          .measurable_steps_h1 = v.measurable_steps_h1,
                          .worst_h3_relative_error = v.worst_h3_relative_error,
                          .measurable_steps_h3 = v.measurable_steps_h3});
  return o;
}

MeasuredBackboneOutcome OutcomeOf(const MeasuredBackboneFile& file) {
  MeasuredBackboneOutcome o{.fit_form = file.single_mode_fit.form,
                            .fit_reduced_chi_square = file.single_mode_fit.reduced_chi_square,
                            .damping_rate_trend = file.damping_trend.verdict,
                            .damping_rate_z = file.damping_trend.damping_rate_z,
                            .damping_ratio_trend = file.damping_trend.damping_ratio_verdict,
                            .damping_ratio_z = file.damping_trend.z};
  for (const auto& l : file.levels) {
    LevelOutcome level{.label = l.label, .jumps = static_cast<int>(l.jumps.size()), .in_global_fit = l.in_global_fit};
    for (const auto& f : l.flags) {
      const std::string name(LevelFlagName(f.kind));
      if (std::find(level.flags.begin(), level.flags.end(), name) == level.flags.end()) level.flags.push_back(name);
    }
    o.flagged_levels += !l.flags.empty();
    o.left_out_levels += !l.in_global_fit;
    o.levels.push_back(level);
  }
  return o;
}

nlohmann::json ToJson(const IdentificationOutcome& o) {
  nlohmann::json held_out = nlohmann::json::array();
  for (const auto& h : o.held_out)
    held_out.push_back({{"channel", h.channel},
                        {"steps", h.steps},
                        {"worst_h1_relative_error", NumberOrNull(h.worst_h1_relative_error)},
                        {"measurable_steps_h1", h.measurable_steps_h1},
                        {"worst_h3_relative_error", NumberOrNull(h.worst_h3_relative_error)},
                        {"measurable_steps_h3", h.measurable_steps_h3}});
  nlohmann::json diagnosis = nullptr;
  if (o.diagnosis)
    diagnosis = {{"verdict", NameOrNull(o.diagnosis->verdict, kDiagnosisVerdictNames)},
                 {"blame", NameOrNull(o.diagnosis->blame, kBlameNames)},
                 {"ranked_by", NameOrNull(o.diagnosis->ranked_by, kRankedByNames)},
                 {"selected", o.diagnosis->selected},
                 {"rest_within_noise", o.diagnosis->rest_within_noise}};
  nlohmann::json damping_law = nullptr;
  if (!o.answer_damping_law.empty())
    damping_law = {{"assumed", o.assumed_damping_law},
                   {"answer", o.answer_damping_law},
                   {"answer_reduced_chi_square", NumberOrNull(o.answer_reduced_chi_square)},
                   {"assumed_rejected", o.assumed_damping_law_rejected}};
  return {{"format", kReportDataFormat},
          {"page", "identification"},
          {"model", {{"kind", NameOrNull(o.model_kind, kModelKindNames)}, {"support_law", o.support_law}}},
          {"fit",
           {{"within_noise", o.fit_within_noise},
            {"chi_square", NumberOrNull(o.chi_square)},
            {"degrees_of_freedom", o.degrees_of_freedom},
            {"reduced_chi_square", NumberOrNull(o.reduced_chi_square)}}},
          {"damping_law", damping_law},
          {"damping_trend",
           {{"verdict", NameOrNull(o.damping_trend, kDampingRateTrendNames)},
            {"z", o.damping_trend == Trend::kNotJudged ? nlohmann::json(nullptr) : NumberOrNull(o.damping_trend_z)}}},
          {"diagnosis", diagnosis},
          {"held_out", held_out}};
}

nlohmann::json ToJson(const MeasuredBackboneOutcome& o) {
  nlohmann::json levels = nlohmann::json::array();
  for (const auto& l : o.levels)
    levels.push_back({{"label", l.label}, {"flags", l.flags}, {"jumps", l.jumps}, {"in_global_fit", l.in_global_fit}});
  const auto trend = [](Trend verdict, double z, const auto& names) {
    return nlohmann::json{{"verdict", NameOrNull(verdict, names)},
                          {"z", verdict == Trend::kNotJudged ? nlohmann::json(nullptr) : NumberOrNull(z)}};
  };
  return {{"format", kReportDataFormat},
          {"page", "measured-backbone"},
          {"levels", levels},
          {"flagged_levels", o.flagged_levels},
          {"left_out_levels", o.left_out_levels},
          {"single_mode_fit", {{"form", o.fit_form}, {"reduced_chi_square", NumberOrNull(o.fit_reduced_chi_square)}}},
          {"damping_rate_trend", trend(o.damping_rate_trend, o.damping_rate_z, kDampingRateTrendNames)},
          {"damping_ratio_trend", trend(o.damping_ratio_trend, o.damping_ratio_z, kDampingRatioTrendNames)}};
}

std::string ReportDataBlock(const nlohmann::json& record) {
  // Non-ASCII as it is (the page is UTF-8); invalid UTF-8 replaced rather than
  // thrown on.
  std::string text = record.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
  // Inside a JSON text "<" stands only in strings, where "\/" and "\u003c"
  // mean what they replace.
  for (std::size_t at = 0; (at = text.find("</", at)) != std::string::npos; at += 3) text.replace(at, 2, "<\\/");
  for (std::size_t at = 0; (at = text.find("<!--", at)) != std::string::npos;) text.replace(at, 1, "\\u003c");
  return "<script type=\"application/json\" id=\"" + std::string(kReportDataId) + "\">" + text + "</script>\n";
}

}  // namespace beamid::solver
