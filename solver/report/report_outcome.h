// The outcomes a report page states, as one record: the fit's verdict, the
// damping law the data accept, the measured damping trend, the diagnosis's
// verdict, the held-out prediction errors (the identification report) or each
// level's flags and jumps and the damping trend (the measured-backbone
// report). Each page builds its record once, from the structs it shows, and
// its headlines, captions and verdicts read their values from it; the page
// embeds the same record as one JSON data block (ReportDataBlock) for
// machines and tests, so what the text says and what the block holds cannot
// drift apart. The block's fields: docs/report.md.
#pragma once

#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "solver/backbone/measured_backbone_io.h"
#include "solver/diagnosis/diagnosis.h"
#include "solver/report/report_curves.h"
#include "solver/report/report_input.h"

namespace beamid::solver {

// The block's "format".
inline constexpr std::string_view kReportDataFormat = "beamid-report-data/1";
// The id of the <script type="application/json"> element that holds it.
inline constexpr std::string_view kReportDataId = "beamid-report-data";

struct HeldOutOutcome {
  std::string channel;
  int steps = 0;
  double worst_h1_relative_error = 0.0;  // NaN (null): no step resolves it
  int measurable_steps_h1 = 0;
  double worst_h3_relative_error = 0.0;
  int measurable_steps_h3 = 0;
};

struct DiagnosisOutcome {
  DiagnosisVerdict verdict = DiagnosisVerdict::kNoSignificantDiscrepancy;
  Blame blame = Blame::kNone;
  RankedBy ranked_by = RankedBy::kNone;
  std::vector<std::string> selected;
  bool rest_within_noise = true;
};

struct IdentificationOutcome {
  ModelKind model_kind = ModelKind::kHarmonicBalance;
  std::string support_law;
  // The fit (result.json fit): χ², its degrees of freedom and the verdict.
  bool fit_within_noise = true;
  double chi_square = 0.0;
  int degrees_of_freedom = 0;
  double reduced_chi_square = 0.0;
  // The damping laws (solver/estimation/damping_laws.h): the law whose
  // parameters are the answer ("" when the laws were not refitted or none
  // converged) and whether the data reject the law the fit assumed.
  std::string assumed_damping_law;
  std::string answer_damping_law;
  double answer_reduced_chi_square = 0.0;
  bool assumed_damping_law_rejected = false;
  // The measured damping rate ζω_n against a constant damper (ReportCurves).
  Trend damping_trend = Trend::kNotJudged;
  double damping_trend_z = 0.0;
  std::optional<DiagnosisOutcome> diagnosis;
  std::vector<HeldOutOutcome> held_out;
};

struct LevelOutcome {
  std::string label;
  std::vector<std::string> flags;  // LevelFlagName of each kind, once, in the file's order
  int jumps = 0;
  bool in_global_fit = true;
};

struct MeasuredBackboneOutcome {
  std::vector<LevelOutcome> levels;
  int flagged_levels = 0;
  int left_out_levels = 0;
  std::string fit_form;
  double fit_reduced_chi_square = 0.0;
  Trend damping_rate_trend = Trend::kNotJudged;  // on ζω_n
  double damping_rate_z = 0.0;
  Trend damping_ratio_trend = Trend::kNotJudged;  // on ζ alone
  double damping_ratio_z = 0.0;
};

IdentificationOutcome OutcomeOf(const ReportInput& input, const ReportCurves& curves);
MeasuredBackboneOutcome OutcomeOf(const MeasuredBackboneFile& file);

nlohmann::json ToJson(const IdentificationOutcome& outcome);
nlohmann::json ToJson(const MeasuredBackboneOutcome& outcome);

// `<script type="application/json" id="beamid-report-data">…</script>`: data,
// never run; every "</" and "<!--" inside is escaped so that no text of the
// record can close the element or open a comment.
std::string ReportDataBlock(const nlohmann::json& record);

}  // namespace beamid::solver
