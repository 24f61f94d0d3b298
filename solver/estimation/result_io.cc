#include "solver/estimation/result_io.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <utility>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "hb/errors.h"
#include "hb/json_field.h"
#include "hb/text_file.h"
#include "solver/estimation/model_family.h"
#include "solver/estimation/model_structure.h"

namespace beamid::solver {
namespace {

// Insertion order: the file lists held-out channels, levels and parameters
// in the order of the fit, and a text read and written again is the same.
using Json = nlohmann::ordered_json;
using Complex = std::complex<double>;

constexpr const char* kFix = "give the result.json that 'beamid identify' wrote (format beamid-result/1)";

// ---- writing ----------------------------------------------------------------

Json PhasorJson(Complex p) { return Json::array({p.real(), p.imag()}); }

Json PhasorsJson(const Eigen::VectorXcd& phasors) {
  Json out = Json::array();
  for (const auto& p : phasors) out.push_back(PhasorJson(p));
  return out;
}

Json MatrixJson(const Eigen::MatrixXd& m) {
  Json out = Json::array();
  for (Eigen::Index r = 0; r < m.rows(); ++r) {
    Json row = Json::array();
    for (Eigen::Index c = 0; c < m.cols(); ++c) row.push_back(m(r, c));
    out.push_back(std::move(row));
  }
  return out;
}

std::string HarmonicKey(std::size_t index) { return "h" + std::to_string(index + 1); }

Json ModelJson(const ResultModel& m) {
  Json masses = Json::array();
  for (const auto& mass : m.sensor_masses) masses.push_back({{"position_m", mass.position_m}, {"mass_kg", mass.mass_kg}});
  return {{"kind", m.kind},
          {"law", m.law},
          {"beam",
           {{"length_m", m.beam.length_m},
            {"width_m", m.beam.width_m},
            {"thickness_m", m.beam.thickness_m},
            {"youngs_modulus_Pa", m.beam.youngs_modulus_Pa},
            {"density_kg_m3", m.beam.density_kg_m3},
            {"loss_factor", m.beam.loss_factor}}},
          {"force_position_m", m.force_position_m},
          {"sensor_masses", masses},
          {"fit_channels", Json(m.fit_channels)},
          {"num_fit_harmonics", m.num_fit_harmonics},
          {"num_harmonics", m.num_harmonics}};
}

Json FitJson(const ResultFit& f) {
  Json starts = Json::array();
  for (const auto& s : f.starts)
    starts.push_back({{"start", Json(s.start)},
                      {"parameters", Json(s.parameters)},
                      {"objective", s.objective},
                      {"converged", s.converged},
                      {"iterations", s.iterations},
                      {"status", s.status},
                      {"states_seeded", s.states_seeded == StartRoute::kMeasuredStates ? "measured" : "feasible"},
                      {"branch_repairs", s.branch_repairs}});
  Json minima = Json::array();
  for (const auto& m : f.minima)
    minima.push_back({{"parameters", Json(m.parameters)}, {"chi_square", m.chi_square}, {"starts", m.num_starts}});
  const ResultDirectEstimate& d = f.direct_estimate;
  return {{"chi_square", f.chi_square},
          {"degrees_of_freedom", f.degrees_of_freedom},
          {"reduced_chi_square", f.reduced_chi_square},
          {"within_noise", f.verdict.within_noise},
          {"verdict", f.verdict.text},
          {"seconds", f.seconds},
          {"starts", starts},
          {"best_start", f.best_start},
          {"starts_at_best", f.starts_at_best},
          {"minima", minima},
          {"second_minimum_chi_square_gap", f.second_minimum_chi_square_gap},
          {"minimum_decisive", f.minimum_decisive},
          {"direct_estimate",
           {{"k1", d.k1_Nm_rad},
            {"k2", d.k2_Nm_rad2},
            {"k3", d.k3_Nm_rad3},
            {"c", d.c_Nms_rad},
            {"relative_residual", d.relative_residual}}}};
}

Json QualityJson(const std::vector<ChannelQuality>& quality) {
  Json out = Json::object();
  for (const auto& channel : quality) {
    Json per_harmonic = Json::object();
    for (std::size_t k = 0; k < channel.harmonics.size(); ++k) {
      Json per_level = Json::object();
      for (const auto& q : channel.harmonics[k])
        per_level[q.level] = {
            {"relative_rms_error", q.relative_rms_error}, {"chi_square", q.chi_square}, {"steps", q.num_steps}};
      per_harmonic[HarmonicKey(k)] = std::move(per_level);
    }
    out[channel.channel] = std::move(per_harmonic);
  }
  return out;
}

Json ValidationJson(const std::vector<HeldOutChannel>& validation) {
  Json out = Json::object();
  for (const auto& channel : validation) {
    Json steps = Json::array();
    for (const auto& s : channel.steps) {
      Json step = {{"level", s.level}, {"file", s.file}, {"frequency_Hz", s.frequency_hz}};
      for (std::size_t k = 0; k < s.harmonics.size(); ++k) {
        const HeldOutHarmonic& h = s.harmonics[k];
        step[HarmonicKey(k) + "_relative_error"] = h.relative_error;
        step[HarmonicKey(k) + "_measured_relative_std"] = h.measured_relative_std;
        step[HarmonicKey(k) + "_predicted"] = PhasorJson(h.predicted);
        step[HarmonicKey(k) + "_measured"] = PhasorJson(h.measured);
      }
      steps.push_back(std::move(step));
    }
    out[channel.channel] = {{"position_m", channel.position_m},
                            {"worst_h1_relative_error", channel.worst_h1_relative_error},
                            {"worst_h3_relative_error", channel.worst_h3_relative_error},
                            {"measurable_relative_std", channel.measurable_relative_std},
                            {"measurable_steps_h1", channel.measurable_steps_h1},
                            {"measurable_steps_h3", channel.measurable_steps_h3},
                            {"steps", steps}};
  }
  return out;
}

Json StepsJson(const std::vector<ResultStep>& steps, const ModelFamily& family) {
  Json out = Json::array();
  for (const auto& s : steps) {
    Json step = {{"level", s.level}, {"file", s.file}, {"frequency_Hz", s.frequency_hz}, {"force_N", PhasorsJson(s.force_N)}};
    step[family.StateName()] = PhasorsJson(s.state);
    out.push_back(std::move(step));
  }
  return out;
}

// ---- reading ----------------------------------------------------------------

// Every value carries its path ("fit.starts[2].objective") for the complaint
// (hb/json_field.h); null is NaN where the fit may not have given a number
// (Number), refused where the model needs one (NumberNotNull).
using Field = JsonField;

Complex FinitePhasor(const Field& f) {
  if (f.Size() != 2) f.Fail("must be a phasor [re, im]");
  return {f.At(0).NumberNotNull(), f.At(1).NumberNotNull()};
}

Eigen::VectorXcd FinitePhasors(const Field& f) {
  Eigen::VectorXcd out(static_cast<Eigen::Index>(f.Size()));
  for (std::size_t i = 0; i < f.Size(); ++i) out[static_cast<Eigen::Index>(i)] = FinitePhasor(f.At(i));
  return out;
}

// size × size, one row per parameter.
Eigen::MatrixXd SquareMatrix(const Field& f, std::size_t size) {
  if (f.Size() != size) f.Fail("must have " + std::to_string(size) + " rows, one per parameter");
  Eigen::MatrixXd out(size, size);
  for (std::size_t r = 0; r < size; ++r) {
    const std::vector<double> row = f.At(r).Numbers();
    if (row.size() != size) f.At(r).Fail("must have " + std::to_string(size) + " columns, one per parameter");
    for (std::size_t c = 0; c < size; ++c) out(r, c) = row[c];
  }
  return out;
}

ResultModel ReadModel(const Field& m) {
  ResultModel out;
  if (m.Has("kind")) out.kind = m.String("kind");  // files from before `--model ms` are hb
  try {
    FindModelFamily(out.kind);
  } catch (const InputError&) {
    m.At("kind").Fail("is '" + out.kind + "': unknown model (" + ModelFamilyNames() + ")");
  }
  out.law = m.String("law");
  const Field b = m.At("beam");
  out.beam = {.length_m = b.At("length_m").NumberNotNull(),
              .width_m = b.At("width_m").NumberNotNull(),
              .thickness_m = b.At("thickness_m").NumberNotNull(),
              .youngs_modulus_Pa = b.At("youngs_modulus_Pa").NumberNotNull(),
              .density_kg_m3 = b.At("density_kg_m3").NumberNotNull(),
              .loss_factor = b.Has("loss_factor") ? b.At("loss_factor").NumberNotNull() : 0.0};
  try {
    out.beam.Validate();
  } catch (const std::invalid_argument& e) {
    b.Fail(std::string("is not a beam's (") + e.what() + ")");
  }
  out.force_position_m = m.At("force_position_m").NumberNotNull();
  for (const Field& mass : m.At("sensor_masses").Elements())
    out.sensor_masses.push_back(
        {.position_m = mass.At("position_m").NumberNotNull(), .mass_kg = mass.At("mass_kg").NumberNotNull()});
  out.fit_channels = m.At("fit_channels").Strings();
  // The ranges identify takes (-H 1..50, --fit-harmonics 1..H).
  out.num_harmonics = m.Integer("num_harmonics");
  if (out.num_harmonics < 1 || out.num_harmonics > 50) m.At("num_harmonics").Fail("must lie in 1..50");
  out.num_fit_harmonics = m.Integer("num_fit_harmonics");
  if (out.num_fit_harmonics < 1 || out.num_fit_harmonics > out.num_harmonics)
    m.At("num_fit_harmonics").Fail("must lie in 1..num_harmonics (" + std::to_string(out.num_harmonics) + ")");
  return out;
}

std::vector<ResultParameter> ReadParameters(const Field& root) {
  const std::vector<std::string> order = root.At("parameter_order").Strings();
  // identify fits the law's few parameters and a few linear ones; the
  // covariance is read as an order × order matrix, allocated before its rows.
  constexpr std::size_t kMaxParameters = 64;
  if (order.size() > kMaxParameters)
    root.At("parameter_order").Fail("names " + std::to_string(order.size()) + " parameters, more than " +
                                    std::to_string(kMaxParameters));
  const Field parameters = root.At("parameters");
  if (parameters.Members().size() != order.size())
    parameters.Fail("holds " + std::to_string(parameters.Members().size()) + " parameters but parameter_order names " +
                    std::to_string(order.size()));
  std::vector<ResultParameter> out;
  for (const auto& name : order) {
    const Field p = parameters.At(name);
    const std::vector<double> ci95 = p.At("ci95").Numbers();
    if (ci95.size() != 2) p.At("ci95").Fail("must be [low, high]");
    out.push_back({.name = name,
                   .unit = p.String("unit"),
                   .value = p.At("value").NumberNotNull(),
                   .std = p.Number("std"),
                   .lower_95 = ci95[0],
                   .upper_95 = ci95[1]});
    // A standard uncertainty is never negative (NaN: the fit gave none).
    if (out.back().std < 0.0) p.At("std").Fail("= " + fmt::format("{:g}", out.back().std) + " is negative");
  }
  return out;
}

// The physical range identify fits each parameter in (model_structure.h:
// k1 >= 0, since a support of negative stiffness pushes the beam away; c >=
// 0; EI_scale in [0.5, 1.5], ...): a value outside it was not written by
// identify, and the model it makes may have no solution. Ipopt may end a
// hair beyond a bound, which the slack allows.
void CheckParameterRanges(const Field& root, const ResultModel& model, const std::vector<ResultParameter>& parameters,
                          const std::vector<std::string>& linear_parameters) {
  if (model.law != "polynomial") return;  // predict refuses other laws, naming the law
  ModelStructure structure = PolynomialModel({});
  for (const auto& name : linear_parameters) {
    try {
      structure.linear.push_back(LinearParameterByName(name, 0.0));
    } catch (const std::invalid_argument&) {
      return;  // an unknown name is refused by predict, naming linear_parameters
    }
  }
  const std::vector<std::string> names = structure.Names();
  const std::vector<ParameterBounds> bounds = structure.Bounds();
  for (const ResultParameter& p : parameters) {
    const auto it = std::find(names.begin(), names.end(), p.name);
    if (it == names.end()) continue;
    const ParameterBounds& b = bounds[static_cast<std::size_t>(it - names.begin())];
    const double slack = 1e-6 * std::max(b.typical, std::max(std::abs(b.lower), std::abs(b.upper)) * 1e-6);
    if (p.value >= b.lower - slack && p.value <= b.upper + slack) continue;
    const Field value = root.At("parameters").At(p.name).At("value");
    const std::string shown = "= " + fmt::format("{:g}", p.value);
    if (b.lower == 0.0 && p.value < 0.0)
      value.Fail(shown + " is negative: " + p.name + " is physical only >= 0 (identify fits it in [0, " +
                 fmt::format("{:g}", b.upper) + "])");
    value.Fail(shown + " lies outside [" + fmt::format("{:g}", b.lower) + ", " + fmt::format("{:g}", b.upper) +
               "], the physical range identify fits " + p.name + " in");
  }
}

Json EstimateJson(const ParameterEstimate& p) {
  return {{"name", p.name}, {"unit", p.unit}, {"value", p.value}, {"std", p.std}, {"ci95", {p.lower_95, p.upper_95}}};
}

Json DampingLawsJson(const DampingLawEnvelope& envelope) {
  Json laws = Json::array();
  for (const auto& law : envelope.laws) {
    Json parameters = Json::array();
    for (const auto& p : law.parameters) parameters.push_back(EstimateJson(p));
    laws.push_back({{"law", law.law},
                    {"converged", law.converged},
                    {"status", law.status},
                    {"chi_square", law.chi_square},
                    {"reduced_chi_square", law.reduced_chi_square},
                    {"accepted", law.accepted},
                    {"parameters", parameters}});
  }
  Json intervals = Json::array();
  for (const auto& i : envelope.intervals)
    intervals.push_back({{"name", i.name},
                         {"unit", i.unit},
                         {"ci95", {i.lower_95, i.upper_95}},
                         {"depends_on_damping_law", i.depends_on_damping_law}});
  return {{"laws", laws}, {"model_form_intervals", intervals}};
}

// EstimateJson's inverse.
ParameterEstimate ReadEstimate(const Field& p) {
  const std::vector<double> ci95 = p.At("ci95").Numbers();
  if (ci95.size() != 2) p.At("ci95").Fail("must be [low, high]");
  return {.name = p.String("name"),
          .unit = p.String("unit"),
          .value = p.Number("value"),
          .std = p.Number("std"),
          .lower_95 = ci95[0],
          .upper_95 = ci95[1]};
}

Json RobustFitJson(const ResultRobustFit& robust) {
  Json outliers = Json::array();
  for (const auto& s : robust.outliers)
    outliers.push_back({{"level", s.level},
                        {"file", s.file},
                        {"frequency_Hz", s.frequency_hz},
                        {"chi_square", s.chi_square},
                        {"num_residuals", s.num_residuals},
                        {"tail_probability", s.tail_probability},
                        {"unsettled", s.unsettled}});
  Json parameters = Json::array();
  for (const auto& p : robust.ordinary_parameters) parameters.push_back(EstimateJson(p));
  return {{"applied", robust.applied},
          {"note", robust.note},
          {"outliers", outliers},
          {"ordinary_fit",
           {{"chi_square", robust.ordinary_chi_square},
            {"degrees_of_freedom", robust.ordinary_degrees_of_freedom},
            {"parameters", parameters}}}};
}

ResultRobustFit ReadRobustFit(const Field& f) {
  ResultRobustFit out{.applied = f.Boolean("applied"), .note = f.String("note")};
  for (const Field& s : f.At("outliers").Elements())
    out.outliers.push_back({.step = -1,
                            .level = s.String("level"),
                            .file = s.String("file"),
                            .frequency_hz = s.Number("frequency_Hz"),
                            .chi_square = s.Number("chi_square"),
                            .num_residuals = s.Integer("num_residuals"),
                            .tail_probability = s.Number("tail_probability"),
                            .unsettled = s.Boolean("unsettled")});
  const Field ordinary = f.At("ordinary_fit");
  out.ordinary_chi_square = ordinary.Number("chi_square");
  out.ordinary_degrees_of_freedom = ordinary.Integer("degrees_of_freedom");
  for (const Field& p : ordinary.At("parameters").Elements()) out.ordinary_parameters.push_back(ReadEstimate(p));
  return out;
}

Json UnsettledStepsJson(const std::vector<ResultUnsettledStep>& steps) {
  Json out = Json::array();
  for (const auto& s : steps)
    out.push_back({{"level", s.level}, {"file", s.file}, {"frequency_Hz", s.frequency_hz}, {"change_relative", s.change_relative}});
  return out;
}

std::vector<ResultUnsettledStep> ReadUnsettledSteps(const Field& f) {
  std::vector<ResultUnsettledStep> out;
  for (const Field& s : f.Elements())
    out.push_back({.level = s.String("level"),
                   .file = s.String("file"),
                   .frequency_hz = s.Number("frequency_Hz"),
                   .change_relative = s.Number("change_relative")});
  return out;
}

// The laws as written; acceptance and intervals judged again from them (one rule).
DampingLawEnvelope ReadDampingLaws(const Field& f) {
  DampingLawEnvelope out;
  for (const Field& law : f.At("laws").Elements()) {
    DampingLawFit fit{.law = law.String("law"),
                      .converged = law.Boolean("converged"),
                      .status = law.String("status"),
                      .chi_square = law.Number("chi_square"),
                      .reduced_chi_square = law.Number("reduced_chi_square")};
    for (const Field& p : law.At("parameters").Elements()) fit.parameters.push_back(ReadEstimate(p));
    out.laws.push_back(std::move(fit));
  }
  JudgeDampingLaws(&out);
  return out;
}

ResultFit ReadFit(const Field& f) {
  ResultFit out;
  out.chi_square = f.Number("chi_square");
  out.degrees_of_freedom = f.Integer("degrees_of_freedom");
  out.reduced_chi_square = f.Number("reduced_chi_square");
  out.verdict = JudgeFit(out.reduced_chi_square);
  if (f.Has("verdict")) out.verdict = {.within_noise = f.Boolean("within_noise"), .text = f.String("verdict")};
  out.seconds = f.At("seconds").NumberNotNull();
  for (const Field& s : f.At("starts").Elements()) {
    const std::string seeded = s.String("states_seeded");
    if (seeded != "measured" && seeded != "feasible") s.At("states_seeded").Fail("must be \"measured\" or \"feasible\"");
    out.starts.push_back({.start = s.At("start").Numbers(),
                          .parameters = s.At("parameters").Numbers(),
                          .objective = s.Number("objective"),
                          .converged = s.Boolean("converged"),
                          .iterations = s.Integer("iterations"),
                          .status = s.String("status"),
                          .states_seeded = seeded == "measured" ? StartRoute::kMeasuredStates : StartRoute::kFeasibleStates,
                          .branch_repairs = s.Integer("branch_repairs")});
  }
  out.best_start = f.Integer("best_start");
  if (out.best_start < 0 || out.best_start >= static_cast<int>(std::max<std::size_t>(out.starts.size(), 1)))
    f.At("best_start").Fail("must be the index of one of fit.starts");
  out.starts_at_best = f.Integer("starts_at_best");
  for (const Field& m : f.At("minima").Elements())
    out.minima.push_back({.parameters = m.At("parameters").Numbers(),
                          .chi_square = m.Number("chi_square"),
                          .num_starts = m.Integer("starts")});
  out.second_minimum_chi_square_gap = f.Number("second_minimum_chi_square_gap");
  out.minimum_decisive = f.Boolean("minimum_decisive");
  const Field d = f.At("direct_estimate");
  out.direct_estimate = {.k1_Nm_rad = d.Number("k1"),
                         .k2_Nm_rad2 = d.Number("k2"),
                         .k3_Nm_rad3 = d.Number("k3"),
                         .c_Nms_rad = d.Number("c"),
                         .relative_residual = d.Number("relative_residual")};
  return out;
}

std::vector<ChannelQuality> ReadQuality(const Field& quality, int num_fit_harmonics) {
  std::vector<ChannelQuality> out;
  for (const auto& [channel, per_harmonic] : quality.Members()) {
    ChannelQuality q{.channel = channel};
    for (int k = 0; k < num_fit_harmonics; ++k) {
      std::vector<LevelQuality> per_level;
      for (const auto& [level, entry] : per_harmonic.At(HarmonicKey(k)).Members())
        per_level.push_back({.level = level,
                             .relative_rms_error = entry.Number("relative_rms_error"),
                             .chi_square = entry.Number("chi_square"),
                             .num_steps = entry.Integer("steps")});
      q.harmonics.push_back(std::move(per_level));
    }
    out.push_back(std::move(q));
  }
  return out;
}

std::vector<HeldOutChannel> ReadValidation(const Field& validation, int num_fit_harmonics) {
  std::vector<HeldOutChannel> out;
  for (const auto& [name, v] : validation.Members()) {
    HeldOutChannel channel{.channel = name,
                           .position_m = v.At("position_m").NumberNotNull(),
                           .worst_h1_relative_error = v.Number("worst_h1_relative_error"),
                           .worst_h3_relative_error = v.Number("worst_h3_relative_error"),
                           .measurable_relative_std = v.At("measurable_relative_std").NumberNotNull(),
                           .measurable_steps_h1 = v.Integer("measurable_steps_h1"),
                           .measurable_steps_h3 = v.Integer("measurable_steps_h3")};
    for (const Field& s : v.At("steps").Elements()) {
      HeldOutStep step{.level = s.String("level"), .file = s.String("file"), .frequency_hz = s.At("frequency_Hz").NumberNotNull()};
      for (int k = 0; k < num_fit_harmonics; ++k) {
        const std::string h = HarmonicKey(k);
        step.harmonics.push_back({.relative_error = s.Number(h + "_relative_error"),
                                  .measured_relative_std = s.Number(h + "_measured_relative_std"),
                                  .predicted = s.At(h + "_predicted").Phasor(),
                                  .measured = s.At(h + "_measured").Phasor()});
      }
      channel.steps.push_back(std::move(step));
    }
    out.push_back(std::move(channel));
  }
  return out;
}

std::vector<ResultStep> ReadSteps(const Field& steps, const ResultModel& model) {
  const ModelFamily& family = FindModelFamily(model.kind);
  const int state_size = family.StateSize(model.num_harmonics);
  std::vector<ResultStep> out;
  for (const Field& s : steps.Elements()) {
    ResultStep step{.level = s.String("level"),
                    .file = s.String("file"),
                    .frequency_hz = s.At("frequency_Hz").NumberNotNull(),
                    .force_N = FinitePhasors(s.At("force_N"))};
    const Field state = s.At(family.StateName());
    step.state = FinitePhasors(state);
    // A model is driven by the force's fundamental at least.
    if (step.state.size() != state_size || step.force_N.size() < 2)
      state.Fail("must hold " + std::to_string(state_size) + " phasor(s) for a " + family.Description() + " model of " +
                 std::to_string(model.num_harmonics) + " harmonics, and force_N the fundamental (step " + step.file + ")");
    out.push_back(std::move(step));
  }
  return out;
}

ResultFile ReadResult(const Json& root, const std::string& source) {
  if (!root.contains("format") || root["format"] != std::string(kResultFormat))
    throw InputError(source + ": not a beamid result (format must be beamid-result/1). Fix: give the result.json "
                     "that 'beamid identify' wrote");
  const Field r(root, "", source, kResultFormat, kFix);
  ResultFile out;
  if (r.Has("beamid_version")) out.beamid_version = r.String("beamid_version");
  const Field campaign = r.At("campaign");
  out.campaign.folder = campaign.String("folder");
  out.campaign.name = campaign.String("name");
  if (campaign.Has("absolute_folder")) out.campaign.absolute_folder = campaign.String("absolute_folder");
  if (r.Has("campaign_sha256")) out.campaign.sha256 = r.String("campaign_sha256");
  out.model = ReadModel(r.At("model"));
  out.parameters = ReadParameters(r);
  out.linear_parameters = r.At("linear_parameters").Strings();
  CheckParameterRanges(r, out.model, out.parameters, out.linear_parameters);
  out.covariance = SquareMatrix(r.At("covariance"), out.parameters.size());
  out.correlation = SquareMatrix(r.At("correlation"), out.parameters.size());
  out.fit = ReadFit(r.At("fit"));
  out.warnings = r.At("warnings").Strings();
  if (r.Has("damping_laws")) out.damping_laws = ReadDampingLaws(r.At("damping_laws"));
  if (r.Has("robust_fit")) out.robust_fit = ReadRobustFit(r.At("robust_fit"));
  if (r.Has("unsettled_steps")) out.unsettled_steps = ReadUnsettledSteps(r.At("unsettled_steps"));
  out.quality = ReadQuality(r.At("quality"), out.model.num_fit_harmonics);
  if (r.Has("validation")) out.validation = ReadValidation(r.At("validation"), out.model.num_fit_harmonics);
  out.steps = ReadSteps(r.At("steps"), out.model);
  return out;
}

}  // namespace

std::string ResultFileToJson(const ResultFile& result) {
  Json root = {{"format", std::string(kResultFormat)}};
  if (!result.beamid_version.empty()) root["beamid_version"] = result.beamid_version;
  root["command"] = "identify";
  root["campaign"] = {{"folder", result.campaign.folder}, {"name", result.campaign.name}};
  if (!result.campaign.absolute_folder.empty()) root["campaign"]["absolute_folder"] = result.campaign.absolute_folder;
  if (!result.campaign.sha256.empty()) root["campaign_sha256"] = result.campaign.sha256;
  root["model"] = ModelJson(result.model);
  Json parameters = Json::object(), order = Json::array();
  for (const auto& p : result.parameters) {
    parameters[p.name] = {
        {"value", p.value}, {"std", p.std}, {"unit", p.unit}, {"ci95", Json::array({p.lower_95, p.upper_95})}};
    order.push_back(p.name);
  }
  root["parameters"] = std::move(parameters);
  root["parameter_order"] = std::move(order);
  root["linear_parameters"] = Json(result.linear_parameters);
  root["covariance"] = MatrixJson(result.covariance);
  root["correlation"] = MatrixJson(result.correlation);
  root["fit"] = FitJson(result.fit);
  if (!result.damping_laws.laws.empty()) root["damping_laws"] = DampingLawsJson(result.damping_laws);
  if (result.robust_fit) root["robust_fit"] = RobustFitJson(*result.robust_fit);
  if (!result.unsettled_steps.empty()) root["unsettled_steps"] = UnsettledStepsJson(result.unsettled_steps);
  root["warnings"] = Json(result.warnings);
  root["quality"] = QualityJson(result.quality);
  if (!result.validation.empty()) root["validation"] = ValidationJson(result.validation);
  root["steps"] = StepsJson(result.steps, FindModelFamily(result.model.kind));
  return root.dump(1) + "\n";
}

ResultFile ResultFileFromJson(const std::string& text, const std::string& source) {
  // Syntax, a root that is no object, and numbers beyond double (1e400).
  return ReadResult(ParseJsonObject(text, source, "beamid result", kFix), source);
}

void WriteResultFile(const std::filesystem::path& file, const ResultFile& result) {
  WriteTextFileAtomically(file, ResultFileToJson(result));
}

ResultFile ReadResultFile(const std::filesystem::path& file) {
  return ResultFileFromJson(
      ReadTextFile(file, "result file", "give the result.json of 'beamid identify', or check the path"), file.string());
}

}  // namespace beamid::solver
