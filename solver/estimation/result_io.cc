#include "solver/estimation/result_io.h"

#include <algorithm>
#include <cstdint>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <type_traits>
#include <utility>

#include <fmt/format.h>

#include "hb/errors.h"
#include "hb/input_limits.h"
#include "hb/json_schema.h"
#include "hb/option_checks.h"
#include "hb/text_file.h"
#include "solver/estimation/damping_laws_schema.h"
#include "solver/estimation/model_family.h"
#include "solver/estimation/model_structure.h"

namespace beamid::solver {
namespace {

using schema::kOmittedWhenEmpty;
using schema::kOptional;
using schema::Presence;
using schema::TextRule;

constexpr schema::Format kResultSchema{kResultFormat, "beamid result",
                                       "give the result.json that 'beamid identify' wrote (format beamid-result/1)"};

// Bounds on what a file can make the reader hold. identify fits the law's few
// parameters and a few linear ones (the covariance is parameters²); a fit
// has tens to thousands of steps and a few starts per parameter.
constexpr std::size_t kMaxParameters = 64;
constexpr std::size_t kMaxStarts = 10'000;
constexpr std::size_t kMaxSteps = 1'000'000;
constexpr std::size_t kMaxLevels = 10'000;
constexpr std::size_t kMaxWarnings = 10'000;
constexpr int kMaxCount = 1'000'000'000;
constexpr std::size_t kMaxPhasors = option_checks::kMaxHarmonics + 1;

std::string HarmonicKey(std::size_t index) { return "h" + std::to_string(index + 1); }

// The keys "h1".."hK" of harmonics 1..K; the documentation names them once
// as "h<k>".
template <typename Io>
std::vector<std::string> HarmonicKeys(int num_fit_harmonics) {
  if constexpr (schema::kDocumenting<Io>) return {"h<k>"};
  std::vector<std::string> keys;
  for (int k = 0; k < num_fit_harmonics; ++k) keys.push_back(HarmonicKey(static_cast<std::size_t>(k)));
  return keys;
}

// On reading, a list the file holds one entry per harmonic of gets that many.
template <typename Io, typename T>
void PerHarmonic(std::vector<T>& v, std::size_t n) {
  if constexpr (Io::kReading) v.resize(n);
}
template <typename Io, typename T>
void PerHarmonic(const std::vector<T>&, std::size_t) {}

// Entry k of such a list; the documentation, which runs on an empty struct,
// gets an empty entry.
template <typename V>
auto& Entry(V& v, std::size_t k) {
  using T = typename std::remove_const_t<V>::value_type;
  static const T kEmpty{};
  if constexpr (std::is_const_v<V>)
    return k < v.size() ? v[k] : kEmpty;
  else
    return v[k];
}

// A rule's words, and when broken what breaks it.
std::string Rule(bool ok, std::string_view rule, const std::string& broken) {
  return ok ? std::string(rule) : std::string(rule) + ": " + broken;
}

using damping_laws_schema::Interval;
using damping_laws_schema::kEstimate;

constexpr auto kRobustFit = [](auto& io, auto& r) {
  io.Boolean("applied", r.applied);
  io.Text("note", r.note);
  io.List("outliers", r.outliers, kMaxSteps, Presence::kRequired, [](auto& step_io, auto& s) {
    step_io.Text("level", s.level);
    step_io.Text("file", s.file);
    step_io.Number("frequency_Hz", s.frequency_hz, "Hz", schema::Positive().OrNull());
    step_io.Number("chi_square", s.chi_square, "1", schema::NonNegative().OrNull());
    step_io.Integer("num_residuals", s.num_residuals, 0, kMaxCount);
    step_io.Number("tail_probability", s.tail_probability, "1", schema::Probability().OrNull());
    step_io.Boolean("unsettled", s.unsettled);
    // The file does not hold the step's index in the ordinary fit's data.
    if constexpr (std::remove_reference_t<decltype(step_io)>::kReading) s.step = -1;
  });
  io.Object("ordinary_fit", r, Presence::kRequired, [](auto& fit_io, auto& f) {
    fit_io.Number("chi_square", f.ordinary_chi_square, "1", schema::NonNegative().OrNull());
    fit_io.Integer("degrees_of_freedom", f.ordinary_degrees_of_freedom, 0, kMaxCount);
    fit_io.List("parameters", f.ordinary_parameters, kMaxParameters, Presence::kRequired, kEstimate);
  });
};

// The physical range identify fits each parameter in (model_structure.h:
// k1 >= 0, since a support of negative stiffness pushes the beam away; c >=
// 0; EI_scale in [0.5, 1.5], ...): a value outside it was not written by
// identify, and the model it makes may have no solution. Ipopt may end a
// hair beyond a bound, which the slack allows. Returns the broken rule's
// words and the parameter's name, or nothing.
std::optional<std::pair<std::string, std::string>> ParameterOutOfRange(const ResultFile& f) {
  if (f.model.law != "polynomial") return std::nullopt;  // predict refuses other laws, naming the law
  ModelStructure structure = PolynomialModel({});
  for (const auto& name : f.linear_parameters) {
    try {
      structure.linear.push_back(LinearParameterByName(name, 0.0));
    } catch (const std::invalid_argument&) {
      return std::nullopt;  // an unknown name is refused by predict, naming linear_parameters
    }
  }
  const std::vector<std::string> names = structure.Names();
  const std::vector<ParameterBounds> bounds = structure.Bounds();
  for (const ResultParameter& p : f.parameters) {
    const auto it = std::find(names.begin(), names.end(), p.name);
    if (it == names.end()) continue;
    const ParameterBounds& b = bounds[static_cast<std::size_t>(it - names.begin())];
    const double slack = 1e-6 * std::max(b.typical, std::max(std::abs(b.lower), std::abs(b.upper)) * 1e-6);
    if (p.value >= b.lower - slack && p.value <= b.upper + slack) continue;
    if (b.lower == 0.0 && p.value < 0.0)
      return std::pair{fmt::format("{} is physical only >= 0 (identify fits it in [0, {:g}]); = {:g} is negative",
                                   p.name, b.upper, p.value),
                       p.name};
    return std::pair{fmt::format("{} lies in [{:g}, {:g}], the physical range identify fits it in; = {:g} does not",
                                 p.name, b.lower, b.upper, p.value),
                     p.name};
  }
  return std::nullopt;
}

}  // namespace

// ---- the declaration of result.json (hb/json_schema.h) ----------------------

void Describe(auto& io, schema::Like<ResultCampaign> auto& c) {
  io.Text("folder", c.folder);
  io.Text("name", c.name);
  io.Text("absolute_folder", c.absolute_folder, TextRule::kAny, kOmittedWhenEmpty);
}

void Describe(auto& io, schema::Like<ResultModel> auto& m) {
  io.Choice("kind", m.kind, kModelKindNames, kOptional);  // files from before `--model ms` are hb
  io.Text("law", m.law, TextRule::kNotEmpty);
  io.Object("beam", m.beam, Presence::kRequired, [](auto& beam_io, auto& b) {
    beam_io.Number("length_m", b.length_m, "m", schema::Positive());
    beam_io.Number("width_m", b.width_m, "m", schema::Positive());
    beam_io.Number("thickness_m", b.thickness_m, "m", schema::Positive());
    beam_io.Number("youngs_modulus_Pa", b.youngs_modulus_Pa, "Pa", schema::Positive());
    beam_io.Number("density_kg_m3", b.density_kg_m3, "kg/m³", schema::Positive());
    beam_io.Number("loss_factor", b.loss_factor, "1", schema::NonNegative(), kOptional);  // 0 in older files
    std::string problem;
    try {
      b.Validate();
    } catch (const std::invalid_argument& e) {
      problem = e.what();
    }
    beam_io.Check(problem.empty(), Rule(problem.empty(), "the beam is a beam's", problem));
  });
  io.Number("force_position_m", m.force_position_m, "m", schema::NonNegative());
  io.List("sensor_masses", m.sensor_masses, hb::kMaxPointsOnBeam, Presence::kRequired, [](auto& mass_io, auto& mass) {
    mass_io.Number("position_m", mass.position_m, "m", schema::NonNegative());
    mass_io.Number("mass_kg", mass.mass_kg, "kg", schema::NonNegative());
  });
  io.Texts("fit_channels", m.fit_channels, hb::kMaxPointsOnBeam, TextRule::kNotEmpty);
  // The ranges identify takes (-H 1..50, --fit-harmonics 1..H).
  io.Integer("num_fit_harmonics", m.num_fit_harmonics, 1, option_checks::kMaxHarmonics);
  io.Integer("num_harmonics", m.num_harmonics, 1, option_checks::kMaxHarmonics);
  // Files from before the propagated uncertainty weighed by the floor.
  io.Choice("phasor_uncertainty", m.phasor_uncertainty, kPhasorUncertaintyNames, kOptional);
  const bool fits = m.num_fit_harmonics <= m.num_harmonics;
  io.Check(fits,
           Rule(fits, "num_fit_harmonics <= num_harmonics",
                fmt::format("{} > {}", m.num_fit_harmonics, m.num_harmonics)),
           "num_fit_harmonics");
}

void Describe(auto& io, schema::Like<ResultFit> auto& f) {
  io.Number("chi_square", f.chi_square, "1", schema::NonNegative().OrNull());
  io.Integer("degrees_of_freedom", f.degrees_of_freedom, 0, kMaxCount);
  io.Number("reduced_chi_square", f.reduced_chi_square, "1", schema::NonNegative().OrNull());
  // Files written before the verdict: judged from reduced_chi_square.
  if constexpr (std::remove_reference_t<decltype(io)>::kReading) f.verdict = JudgeFit(f.reduced_chi_square);
  io.Boolean("within_noise", f.verdict.within_noise, kOptional);
  io.Text("verdict", f.verdict.text, TextRule::kAny, kOptional);
  io.Number("seconds", f.seconds, "s", schema::NonNegative());
  io.List("starts", f.starts, kMaxStarts, Presence::kRequired, [](auto& start_io, auto& s) {
    static constexpr schema::Name<StartRoute> kRoutes[] = {{StartRoute::kMeasuredStates, "measured"},
                                                          {StartRoute::kFeasibleStates, "feasible"}};
    start_io.Numbers("start", s.start, "the parameters' units", schema::Any().OrNull(), kMaxParameters);
    start_io.Numbers("parameters", s.parameters, "the parameters' units", schema::Any().OrNull(), kMaxParameters);
    start_io.Number("objective", s.objective, "1", schema::NonNegative().OrNull());
    start_io.Boolean("converged", s.converged);
    start_io.Integer("iterations", s.iterations, 0, kMaxCount);
    start_io.Text("status", s.status);
    start_io.Choice("states_seeded", s.states_seeded, kRoutes);
    start_io.Integer("branch_repairs", s.branch_repairs, 0, kMaxCount);
  });
  io.Integer("best_start", f.best_start, 0, static_cast<std::int64_t>(kMaxStarts));
  const bool best = f.best_start < static_cast<int>(std::max<std::size_t>(f.starts.size(), 1));
  io.Check(best, "best_start is the index of one of starts", "best_start");
  io.Integer("starts_at_best", f.starts_at_best, 0, static_cast<std::int64_t>(kMaxStarts));
  io.List("minima", f.minima, kMaxStarts, Presence::kRequired, [](auto& minimum_io, auto& m) {
    minimum_io.Numbers("parameters", m.parameters, "the parameters' units", schema::Any().OrNull(), kMaxParameters);
    minimum_io.Number("chi_square", m.chi_square, "1", schema::NonNegative().OrNull());
    minimum_io.Integer("starts", m.num_starts, 0, static_cast<std::int64_t>(kMaxStarts));
  });
  io.Number("second_minimum_chi_square_gap", f.second_minimum_chi_square_gap, "1", schema::NonNegative().OrNull());
  io.Boolean("minimum_decisive", f.minimum_decisive);
  io.Object("direct_estimate", f.direct_estimate, Presence::kRequired, [](auto& d_io, auto& d) {
    d_io.Number("k1", d.k1_Nm_rad, "N m/rad", schema::Any().OrNull());
    d_io.Number("k2", d.k2_Nm_rad2, "N m/rad²", schema::Any().OrNull());
    d_io.Number("k3", d.k3_Nm_rad3, "N m/rad³", schema::Any().OrNull());
    d_io.Number("c", d.c_Nms_rad, "N m s/rad", schema::Any().OrNull());
    d_io.Number("relative_residual", d.relative_residual, "1", schema::NonNegative().OrNull());
  });
  // Harmonics 1..K in order; written only with calibrated phasor σ.
  io.List("model_errors", f.model_errors, static_cast<std::size_t>(option_checks::kMaxHarmonics), kOmittedWhenEmpty,
          [](auto& e_io, auto& e) {
            e_io.Number("relative", e.relative, "1", schema::NonNegative().OrNull());
            Interval(e_io, "ci95", e.lower_95, e.upper_95, "1");
            e_io.Number("chi_square", e.chi_square, "1", schema::NonNegative().OrNull());
            e_io.Number("degrees_of_freedom", e.degrees_of_freedom, "1", schema::NonNegative().OrNull());
          });
}

void Describe(auto& io, schema::Like<ResultUnsettledStep> auto& s) {
  io.Text("level", s.level);
  io.Text("file", s.file);
  io.Number("frequency_Hz", s.frequency_hz, "Hz", schema::Positive().OrNull());
  io.Number("change_relative", s.change_relative, "1", schema::NonNegative().OrNull());
}

void Describe(auto& io, schema::Like<ResultFile> auto& f) {
  using Io = std::remove_reference_t<decltype(io)>;
  io.Constant("format", kResultFormat);
  io.Text("beamid_version", f.beamid_version, TextRule::kAny, kOmittedWhenEmpty);
  io.Constant("command", "identify");
  io.Object("campaign", f.campaign);
  io.Text("campaign_sha256", f.campaign.sha256, TextRule::kAny, kOmittedWhenEmpty);
  io.Object("model", f.model);

  // The parameters keyed by name, and their order (the structure's: law,
  // then linear), which the keys of an object do not keep.
  io.Keyed("parameters", f.parameters, &ResultParameter::name, kMaxParameters, Presence::kRequired,
           [](auto& p_io, auto& p) {
             p_io.Number("value", p.value, "the parameter's unit");
             p_io.Number("std", p.std, "the parameter's unit", schema::NonNegative().OrNull());
             p_io.Text("unit", p.unit);
             Interval(p_io, "ci95", p.lower_95, p.upper_95, "the parameter's unit");
             // Files from before the residual model error was estimated: 0.
             p_io.Number("std_model_error", p.std_model_error, "the parameter's unit", schema::NonNegative().OrNull(),
                         kOptional);
           });
  std::vector<std::string> order;
  for (const ResultParameter& p : f.parameters) order.push_back(p.name);
  io.Texts("parameter_order", order, kMaxParameters, TextRule::kNotEmpty);
  if constexpr (Io::kReading) {
    std::vector<ResultParameter> ordered;
    for (const std::string& name : order) {
      const auto it = std::find_if(f.parameters.begin(), f.parameters.end(),
                                   [&](const ResultParameter& p) { return p.name == name; });
      if (it == f.parameters.end()) break;
      ordered.push_back(*it);
    }
    const bool same = ordered.size() == f.parameters.size() && order.size() == f.parameters.size();
    io.Check(same,
             Rule(same, "parameters holds exactly the parameters parameter_order names",
                  fmt::format("it holds {}, parameter_order names {}", f.parameters.size(), order.size())),
             "parameters");
    f.parameters = std::move(ordered);
  } else {
    io.Check(true, "parameters holds exactly the parameters parameter_order names", "parameters");
  }
  io.Texts("linear_parameters", f.linear_parameters, kMaxParameters, TextRule::kNotEmpty);
  const auto out_of_range = ParameterOutOfRange(f);
  io.Check(!out_of_range,
           out_of_range ? out_of_range->first : "a parameter lies in the physical range identify fits it in",
           out_of_range ? "parameters." + out_of_range->second + ".value" : std::string());

  const schema::Count per_parameter = schema::Count::Exactly(f.parameters.size(), "one per parameter");
  io.Matrix("covariance", f.covariance, "unit_i · unit_j", schema::Any().OrNull(), per_parameter, per_parameter);
  // Rounding may carry a correlation a hair beyond ±1.
  io.Matrix("correlation", f.correlation, "1", schema::Between(-1.0 - 1e-6, 1.0 + 1e-6).OrNull(), per_parameter,
            per_parameter);
  io.Object("fit", f.fit);
  io.Object("damping_laws", f.damping_laws, kOmittedWhenEmpty, damping_laws_schema::kEnvelope);
  io.Object("robust_fit", f.robust_fit, kOmittedWhenEmpty, kRobustFit);
  io.List("unsettled_steps", f.unsettled_steps, kMaxSteps, kOmittedWhenEmpty);
  io.Texts("warnings", f.warnings, kMaxWarnings);

  // Per fitted channel, harmonic ("h1".."hK") and level.
  const std::vector<std::string> harmonics = HarmonicKeys<Io>(f.model.num_fit_harmonics);
  io.Keyed("quality", f.quality, &ChannelQuality::channel, hb::kMaxPointsOnBeam, Presence::kRequired,
           [&](auto& channel_io, auto& c) {
             PerHarmonic<Io>(c.harmonics, harmonics.size());
             channel_io.Check(c.harmonics.size() == harmonics.size(), "one entry per fitted harmonic");
             for (std::size_t k = 0; k < harmonics.size(); ++k)
               channel_io.Keyed(harmonics[k], Entry(c.harmonics, k), &LevelQuality::level, kMaxLevels,
                                Presence::kRequired,
                                [](auto& level_io, auto& q) {
                                  level_io.Number("relative_rms_error", q.relative_rms_error, "1",
                                                  schema::NonNegative().OrNull());
                                  level_io.Number("chi_square", q.chi_square, "1", schema::NonNegative().OrNull());
                                  level_io.Integer("steps", q.num_steps, 0, kMaxCount);
                                  level_io.Object("relative_std", q.relative_std, kOptional, [](auto& u_io, auto& u) {
                                    u_io.Number("noise", u.noise, "1", schema::NonNegative());
                                    u_io.Number("force", u.force, "1", schema::NonNegative());
                                    u_io.Number("frequency", u.frequency, "1", schema::NonNegative());
                                    u_io.Number("model_error", u.model_error, "1", schema::NonNegative());
                                  });
                                });
           });

  // Per held-out channel and step, the keys "hk_..." of harmonics 1..K.
  io.Keyed("validation", f.validation, &HeldOutChannel::channel, hb::kMaxPointsOnBeam, kOmittedWhenEmpty,
           [&](auto& channel_io, auto& v) {
             channel_io.Number("position_m", v.position_m, "m", schema::NonNegative());
             channel_io.Number("worst_h1_relative_error", v.worst_h1_relative_error, "1",
                               schema::NonNegative().OrNull());
             channel_io.Number("worst_h3_relative_error", v.worst_h3_relative_error, "1",
                               schema::NonNegative().OrNull());
             channel_io.Number("measurable_relative_std", v.measurable_relative_std, "1", schema::Positive());
             channel_io.Integer("measurable_steps_h1", v.measurable_steps_h1, 0, kMaxCount);
             channel_io.Integer("measurable_steps_h3", v.measurable_steps_h3, 0, kMaxCount);
             channel_io.List("steps", v.steps, kMaxSteps, Presence::kRequired, [&](auto& step_io, auto& s) {
               step_io.Text("level", s.level);
               step_io.Text("file", s.file);
               step_io.Number("frequency_Hz", s.frequency_hz, "Hz", schema::Positive());
               PerHarmonic<Io>(s.harmonics, harmonics.size());
               step_io.Check(s.harmonics.size() == harmonics.size(), "one entry per fitted harmonic");
               for (std::size_t k = 0; k < harmonics.size(); ++k) {
                 auto& h = Entry(s.harmonics, k);
                 const std::string& key = harmonics[k];
                 step_io.Number(key + "_relative_error", h.relative_error, "1", schema::NonNegative().OrNull());
                 step_io.Number(key + "_measured_relative_std", h.measured_relative_std, "1",
                                schema::NonNegative().OrNull());
                 step_io.Phasor(key + "_predicted", h.predicted, "the channel's quantity", schema::Any().OrNull());
                 step_io.Phasor(key + "_measured", h.measured, "the channel's quantity", schema::Any().OrNull());
               }
             });
           });

  // The model's steady state at each fitted step, under its family's name
  // ("theta_rad": Θ_0..Θ_H, "modal_phasor_m": U).
  const ModelFamily& family = FindModelFamily(f.model.kind);
  const std::string state_name = family.StateName();
  const auto state_size = static_cast<std::size_t>(family.StateSize(f.model.num_harmonics));
  io.List("steps", f.steps, kMaxSteps, Presence::kRequired, [&](auto& step_io, auto& s) {
    step_io.Text("level", s.level);
    step_io.Text("file", s.file);
    step_io.Number("frequency_Hz", s.frequency_hz, "Hz", schema::Positive());
    step_io.Phasors("force_N", s.force_N, "N", schema::Any(), kMaxPhasors);
    step_io.Check(s.force_N.size() >= 2, "force_N holds the fundamental F_1 at least", "force_N");
    step_io.Phasors(state_name, s.state, state_name == "theta_rad" ? "rad" : "m", schema::Any(),
                    schema::Count::Exactly(state_size, "the model's state size (theta_rad: num_harmonics + 1, "
                                                       "modal_phasor_m: 1)"));
  });
}

std::vector<schema::FieldDoc> ResultFileFields() { return schema::Fields<ResultFile>(); }

std::string ResultFileToJson(const ResultFile& result) { return schema::ToJson(result); }

ResultFile ResultFileFromJson(const std::string& text, const std::string& source) {
  ResultFile result = schema::FromJson<ResultFile>(text, source, kResultSchema);
  // The laws as written; acceptance and intervals judged again from them (one rule).
  if (!result.damping_laws.laws.empty()) JudgeDampingLaws(&result.damping_laws);
  return result;
}

void WriteResultFile(const std::filesystem::path& file, const ResultFile& result) {
  WriteTextFileAtomically(file, ResultFileToJson(result));
}

ResultFile ReadResultFile(const std::filesystem::path& file) {
  return ResultFileFromJson(
      ReadTextFile(file, "result file", "give the result.json of 'beamid identify', or check the path"), file.string());
}

}  // namespace beamid::solver
