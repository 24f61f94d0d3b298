#include "solver/live/test_plan_io.h"

#include <nlohmann/json.hpp>

#include "hb/json_field.h"
#include "hb/strict_json.h"
#include "hb/text_file.h"

namespace beamid::solver {

namespace {
constexpr std::string_view kFormatDoc = "docs/test-plan-format.md";
constexpr std::string_view kFix = "let beamid watch write the plan (docs/test-plan-format.md)";
}  // namespace

std::string TestPlanJson(const TestPlan& plan) {
  nlohmann::ordered_json j;
  j["format"] = kTestPlanFormat;
  j["sequence"] = plan.sequence;
  j["done"] = plan.done;
  j["done_reason"] = plan.done_reason;
  if (plan.next) {
    const PlannedStep& s = *plan.next;
    j["next"] = {{"level", s.level},
                 {"force_N", s.force_N},
                 {"frequency_Hz", s.frequency_hz},
                 {"settle_s", s.settle_s},
                 {"record_s", s.record_s},
                 {"repeat", s.repeat},
                 {"sweep", s.sweep == SweepDirection::kDown ? "down" : "up"},
                 {"reason", s.reason},
                 {"expected_gain_nats", s.expected_gain},
                 {"expected_gain_nats_per_s", s.expected_gain_per_s}};
  } else {
    j["next"] = nullptr;
  }
  j["steps_analysed"] = plan.steps_analysed;
  j["rig_time_s"] = plan.rig_time_s;
  j["parameters"] = nlohmann::ordered_json::array();
  for (const PlanParameter& p : plan.parameters)
    j["parameters"].push_back({{"name", p.name},
                               {"unit", p.unit},
                               {"value", p.value},
                               {"std", p.std},
                               {"target_std", p.target_std},
                               {"lower_95", p.lower_95},
                               {"upper_95", p.upper_95},
                               {"depends_on_damping_law", p.depends_on_damping_law}});
  j["reduced_chi_square"] = plan.reduced_chi_square;
  j["fit_verdict"] = plan.fit_verdict;
  j["warnings"] = plan.warnings;
  j["model"] = plan.model;
  j["intervals"] = plan.intervals;
  if (plan.diagnosis) {
    const PlanDiagnosis& d = *plan.diagnosis;
    j["diagnosis"] = {{"steps", d.steps},
                      {"verdict", d.verdict},
                      {"selected", d.selected},
                      {"summary", d.summary},
                      {"model_extended", d.model_extended},
                      {"focus_level", d.focus_level},
                      {"focus_low_Hz", d.focus_low_hz},
                      {"focus_high_Hz", d.focus_high_hz},
                      {"seconds", d.seconds}};
  } else {
    j["diagnosis"] = nullptr;
  }
  return j.dump(2) + "\n";
}

void WriteTestPlan(const std::filesystem::path& path, const TestPlan& plan) {
  WriteTextFileAtomically(path, TestPlanJson(plan));
}

TestPlan ParseTestPlan(const std::string& text, const std::string& source) {
  const nlohmann::ordered_json json = ParseStrictJson(text, source, kFormatDoc);
  const JsonField root(json, "", source, kTestPlanFormat, kFix);
  root.OnlyKeys({"format", "sequence", "done", "done_reason", "next", "steps_analysed", "rig_time_s", "parameters",
                 "reduced_chi_square", "fit_verdict", "warnings", "model", "intervals", "diagnosis"});
  if (root.At("format").String() != kTestPlanFormat) root.At("format").Fail("is not " + std::string(kTestPlanFormat));
  TestPlan plan;
  plan.sequence = root.At("sequence").Integer();
  plan.done = root.At("done").Boolean();
  plan.done_reason = root.At("done_reason").String();
  if (!root.At("next").json().is_null()) {
    const JsonField next = root.At("next");
    next.OnlyKeys({"level", "force_N", "frequency_Hz", "settle_s", "record_s", "repeat", "sweep", "reason",
                   "expected_gain_nats", "expected_gain_nats_per_s"});
    plan.next = PlannedStep{.level = next.At("level").String(),
                            .force_N = next.At("force_N").Number(),
                            .frequency_hz = next.At("frequency_Hz").Number(),
                            .settle_s = next.At("settle_s").Number(),
                            .record_s = next.At("record_s").Number(),
                            .reason = next.At("reason").String(),
                            .expected_gain = next.At("expected_gain_nats").Number(),
                            .expected_gain_per_s = next.At("expected_gain_nats_per_s").Number(),
                            .repeat = next.At("repeat").Boolean()};
    // Plans written before levels were swept downwards have no "sweep": every level went up.
    if (next.Has("sweep")) {
      const std::string sweep = next.At("sweep").String();
      if (sweep != "up" && sweep != "down") next.At("sweep").Fail("must be \"up\" or \"down\"");
      plan.next->sweep = sweep == "down" ? SweepDirection::kDown : SweepDirection::kUp;
    }
    if (!(plan.next->frequency_hz > 0.0)) next.At("frequency_Hz").Fail("must be positive");
    if (!(plan.next->settle_s >= 0.0)) next.At("settle_s").Fail("must not be negative");
    if (!(plan.next->record_s > 0.0)) next.At("record_s").Fail("must be positive");
    if (!(plan.next->force_N > 0.0)) next.At("force_N").Fail("must be positive");
  }
  plan.steps_analysed = root.At("steps_analysed").Integer();
  plan.rig_time_s = root.At("rig_time_s").Number();
  for (const JsonField& p : root.At("parameters").Elements()) {
    p.OnlyKeys({"name", "unit", "value", "std", "target_std", "lower_95", "upper_95", "depends_on_damping_law"});
    plan.parameters.push_back({.name = p.At("name").String(),
                               .unit = p.At("unit").String(),
                               .value = p.At("value").Number(),
                               .std = p.At("std").Number(),
                               .target_std = p.At("target_std").Number(),
                               .lower_95 = p.At("lower_95").Number(),
                               .upper_95 = p.At("upper_95").Number(),
                               .depends_on_damping_law = p.At("depends_on_damping_law").Boolean()});
  }
  plan.reduced_chi_square = root.At("reduced_chi_square").Number();
  plan.fit_verdict = root.At("fit_verdict").String();
  plan.warnings = root.At("warnings").Strings();
  plan.model = root.At("model").String();
  plan.intervals = root.At("intervals").String();
  if (!root.At("diagnosis").json().is_null()) {
    const JsonField d = root.At("diagnosis");
    d.OnlyKeys({"steps", "verdict", "selected", "summary", "model_extended", "focus_level", "focus_low_Hz",
                "focus_high_Hz", "seconds"});
    plan.diagnosis = PlanDiagnosis{.steps = d.At("steps").Integer(),
                                   .verdict = d.At("verdict").String(),
                                   .selected = d.At("selected").Strings(),
                                   .summary = d.At("summary").String(),
                                   .model_extended = d.At("model_extended").Boolean(),
                                   .focus_level = d.At("focus_level").String(),
                                   .focus_low_hz = d.At("focus_low_Hz").Number(),
                                   .focus_high_hz = d.At("focus_high_Hz").Number(),
                                   .seconds = d.At("seconds").Number()};
  }
  return plan;
}

TestPlan ReadTestPlan(const std::filesystem::path& path) {
  return ParseTestPlan(ReadTextFile(path, "test plan", "give the plan file beamid watch writes"), path.string());
}

}  // namespace beamid::solver
