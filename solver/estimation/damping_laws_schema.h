// How a file holds a damping-law envelope (solver/estimation/damping_laws.h):
// each law's refit with its estimates, and the model-form intervals. One
// declaration (hb/json_schema.h) for every file that carries one: identify's
// result.json and, for the selected model, diagnose's diagnosis.json.
#pragma once

#include <cstddef>
#include <string_view>
#include <vector>

#include "hb/json_schema.h"
#include "solver/estimation/damping_laws.h"

namespace beamid::solver::damping_laws_schema {

inline constexpr std::size_t kMaxLaws = 16;
inline constexpr std::size_t kMaxParameters = 64;

// Two members the file holds as one [low, high].
template <typename Io, typename D>
void Interval(Io& io, std::string_view key, D& low, D& high, std::string_view unit,
              schema::Presence presence = schema::Presence::kRequired) {
  std::vector<double> pair = {low, high};
  io.Numbers(key, pair, unit, schema::Any().OrNull(), schema::Count::Exactly(2, "2 (low, high)"), presence);
  if constexpr (Io::kReading) {
    low = pair[0];
    high = pair[1];
  }
}

// A fit's estimate of one parameter, in a list that names it.
inline constexpr auto kEstimate = [](auto& io, auto& p) {
  io.Text("name", p.name, schema::TextRule::kNotEmpty);
  io.Text("unit", p.unit);
  io.Number("value", p.value, "the parameter's unit", schema::Any().OrNull());
  io.Number("std", p.std, "the parameter's unit", schema::NonNegative().OrNull());
  Interval(io, "ci95", p.lower_95, p.upper_95, "the parameter's unit");
};

// The envelope. A reader judges the laws again (JudgeDampingLaws), which
// also rebuilds the intervals from the laws and the truncation refit, so a
// file cannot claim an acceptance or an interval its numbers do not support.
inline constexpr auto kEnvelope = [](auto& io, auto& envelope) {
  using schema::Presence;
  using schema::TextRule;
  io.List("laws", envelope.laws, kMaxLaws, Presence::kRequired, [](auto& law_io, auto& law) {
    law_io.Text("law", law.law, TextRule::kNotEmpty);
    law_io.Boolean("converged", law.converged);
    law_io.Text("status", law.status);
    law_io.Number("chi_square", law.chi_square, "1", schema::NonNegative().OrNull());
    law_io.Number("reduced_chi_square", law.reduced_chi_square, "1", schema::NonNegative().OrNull());
    law_io.Boolean("accepted", law.accepted);
    law_io.List("parameters", law.parameters, kMaxParameters, Presence::kRequired, kEstimate);
  });
  io.Object("truncation", envelope.truncation, Presence::kOptional, [](auto& t_io, auto& t) {
    t_io.Integer("model_harmonics", t.model_harmonics, 1, 1000);
    t_io.Integer("refit_harmonics", t.refit_harmonics, 1, 1000);
    t_io.Boolean("converged", t.converged);
    t_io.Text("status", t.status);
    t_io.List("parameters", t.parameters, kMaxParameters, Presence::kRequired, kEstimate);
  });
  io.List("model_form_intervals", envelope.intervals, kMaxParameters, Presence::kRequired,
          [](auto& interval_io, auto& i) {
            interval_io.Text("name", i.name, TextRule::kNotEmpty);
            interval_io.Text("unit", i.unit);
            Interval(interval_io, "ci95", i.lower_95, i.upper_95, "the parameter's unit");
            // Rebuilt on reading; older files lack the parts.
            Interval(interval_io, "statistical_ci95", i.statistical_lower_95, i.statistical_upper_95,
                     "the parameter's unit", Presence::kOptional);
            Interval(interval_io, "damping_law_ci95", i.damping_law_lower_95, i.damping_law_upper_95,
                     "the parameter's unit", Presence::kOptional);
            interval_io.Number("truncation_shift", i.truncation_shift, "the parameter's unit", schema::Any(),
                               Presence::kOptional);
            interval_io.Boolean("depends_on_damping_law", i.depends_on_damping_law);
            interval_io.Boolean("depends_on_truncation", i.depends_on_truncation, Presence::kOptional);
          });
};

}  // namespace beamid::solver::damping_laws_schema
