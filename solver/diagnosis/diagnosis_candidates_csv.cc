#include "solver/diagnosis/diagnosis_candidates_csv.h"

#include <algorithm>

#include <fmt/core.h>

#include "hb/csv_cell.h"

namespace beamid::solver {
namespace {

using hb::CsvNumber;
using hb::CsvText;

// The candidate's own parameters (not the base model's), in one cell.
std::string OwnParameters(const CandidateOutcome& c) {
  std::string text;
  for (const ParameterEstimate& p : c.fit.parameters) {
    if (std::find(c.extra_parameters.begin(), c.extra_parameters.end(), p.name) == c.extra_parameters.end()) continue;
    text += fmt::format("{}{} = {:.6g} ± {:.2g}{}", text.empty() ? "" : "; ", p.name, p.value, p.std,
                        p.unit.empty() ? "" : " " + p.unit);
  }
  return text;
}

std::string Row(const std::string& kind, const std::string& rank, const std::string& named, const std::string& name,
                const FitSummary& fit, const CandidateOutcome* c) {
  const bool refitted = !c || c->Refitted();
  const auto fitted = [&](double value, std::string_view format) { return refitted ? CsvNumber(value, format) : ""; };
  return fmt::format(
      "{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{}\n", kind, rank, CsvText(name), named,
      c ? CsvNumber(c->signature_score, "{:.3f}") : "",
      CsvText(c ? std::string(schema::NameOf(c->status, kRefitStatusNames)) : "refitted"),
      c && c->measurement ? "yes" : "no", fitted(fit.chi_square, "{:.9g}"),
      refitted ? std::to_string(fit.degrees_of_freedom) : "", fitted(fit.reduced_chi_square, "{:.6g}"),
      fitted(fit.aic, "{:.9g}"), fitted(fit.bic, "{:.9g}"), c && refitted ? CsvNumber(c->likelihood_ratio, "{:.6g}") : "",
      c && refitted ? std::to_string(c->test_dof) : "", c && refitted ? CsvNumber(c->p_value, "{:.3g}") : "",
      c && refitted ? (c->significant ? "yes" : "no") : "", c && refitted ? CsvNumber(c->residual_drop, "{:.6g}") : "",
      fitted(fit.held_out_chi_square, "{:.6g}"), fitted(fit.held_out_h1_relative_error, "{:.4g}"),
      c ? CsvText(OwnParameters(*c)) : "", c ? CsvText(c->status_message) : "", c ? CsvText(c->rig_check) : "");
}

}  // namespace

std::string DiagnosisCandidatesCsv(const DiagnosisResult& diagnosis) {
  std::string csv =
      "kind,rank,name,named,signature_score,status,measurement,chi_square,degrees_of_freedom,reduced_chi_square,aic,"
      "bic,likelihood_ratio,test_dof,p_value,significant,residual_drop,held_out_chi_square,"
      "held_out_h1_relative_error,own_parameters,status_message,rig_check\n";
  csv += Row("base", "", "", "base model", diagnosis.base, nullptr);
  // The verdict on the rows it names: the cause, the two indistinguishable
  // ones, or the cause and its pair.
  const std::string verdict(schema::NameOf(diagnosis.verdict, kDiagnosisVerdictNames));
  const auto& selected = diagnosis.selected;
  const auto named = [&](const std::string& name) {
    const bool in_selected = std::find(selected.begin(), selected.end(), name) != selected.end();
    const bool the_pair = selected.size() == 2 && name == selected[0] + " + " + selected[1];
    return in_selected || the_pair ? CsvText(verdict) : std::string();
  };
  for (std::size_t i = 0; i < diagnosis.candidates.size(); ++i) {
    const CandidateOutcome& c = diagnosis.candidates[i];
    csv += Row("candidate", std::to_string(i + 1), named(c.name), c.name, c.fit, &c);
  }
  for (std::size_t i = 0; i < diagnosis.combinations.size(); ++i) {
    const CandidateOutcome& c = diagnosis.combinations[i];
    csv += Row("pair", std::to_string(i + 1), named(c.name), c.name, c.fit, &c);
  }
  return csv;
}

}  // namespace beamid::solver
