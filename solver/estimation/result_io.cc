#include "solver/estimation/result_io.h"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <utility>

#include <nlohmann/json.hpp>

#include "hb/errors.h"
#include "hb/text_file.h"
#include "solver/estimation/model_family.h"

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

// A value of the file with its path ("fit.starts[2].objective"), so that
// every complaint names the field.
class Field {
 public:
  Field(const Json& json, std::string path, const std::string& source)
      : json_(&json), path_(std::move(path)), source_(&source) {}

  [[noreturn]] void Fail(const std::string& problem) const {
    throw InputError(*source_ + ": field '" + path_ + "' " + problem + ". Fix: " + kFix);
  }

  bool Has(const std::string& key) const { return json_->is_object() && json_->contains(key); }

  Field operator[](const std::string& key) const {
    RequireObject();
    const auto it = json_->find(key);
    const std::string path = path_.empty() ? key : path_ + "." + key;
    if (it == json_->end()) Field(*json_, path, *source_).Fail("is missing");
    return Field(*it, path, *source_);
  }

  std::vector<Field> Elements() const {
    if (!json_->is_array()) Fail(std::string("must be an array (it is ") + json_->type_name() + ")");
    std::vector<Field> out;
    for (std::size_t i = 0; i < json_->size(); ++i)
      out.emplace_back((*json_)[i], path_ + "[" + std::to_string(i) + "]", *source_);
    return out;
  }

  std::vector<std::pair<std::string, Field>> Members() const {
    RequireObject();
    std::vector<std::pair<std::string, Field>> out;
    for (auto it = json_->begin(); it != json_->end(); ++it)
      out.emplace_back(it.key(), Field(it.value(), path_ + "." + it.key(), *source_));
    return out;
  }

  std::size_t Size() const { return json_->size(); }

  double Number() const {
    if (!json_->is_number()) Fail(std::string("must be a number (it is ") + json_->type_name() + ")");
    return json_->get<double>();
  }
  // A statistic the fit may not have given: null (a NaN when written) is NaN.
  double NumberOrNaN() const {
    return json_->is_null() ? std::numeric_limits<double>::quiet_NaN() : Number();
  }
  int Integer() const {
    const double value = json_->is_number() ? json_->get<double>() : std::nan("");
    if (!json_->is_number() || value != std::floor(value) || std::abs(value) > std::numeric_limits<int>::max())
      Fail(std::string("must be an integer (it is ") + (json_->is_number() ? json_->dump() : json_->type_name()) + ")");
    return static_cast<int>(value);
  }
  bool Boolean() const {
    if (!json_->is_boolean()) Fail(std::string("must be true or false (it is ") + json_->type_name() + ")");
    return json_->get<bool>();
  }
  std::string String() const {
    if (!json_->is_string()) Fail(std::string("must be a string (it is ") + json_->type_name() + ")");
    return json_->get<std::string>();
  }

  std::vector<std::string> Strings() const {
    std::vector<std::string> out;
    for (const Field& e : Elements()) out.push_back(e.String());
    return out;
  }
  std::vector<double> NumbersOrNaN() const {
    std::vector<double> out;
    for (const Field& e : Elements()) out.push_back(e.NumberOrNaN());
    return out;
  }
  // [re, im]; `nan_allowed` for the statistics of a prediction.
  Complex Phasor(bool nan_allowed = false) const {
    const std::vector<Field> parts = Elements();
    if (parts.size() != 2) Fail("must be a phasor [re, im]");
    return nan_allowed ? Complex(parts[0].NumberOrNaN(), parts[1].NumberOrNaN())
                       : Complex(parts[0].Number(), parts[1].Number());
  }
  Eigen::VectorXcd Phasors() const {
    const std::vector<Field> items = Elements();
    Eigen::VectorXcd out(static_cast<Eigen::Index>(items.size()));
    for (std::size_t i = 0; i < items.size(); ++i) out[static_cast<Eigen::Index>(i)] = items[i].Phasor();
    return out;
  }
  // size × size, one row per parameter.
  Eigen::MatrixXd SquareMatrix(std::size_t size) const {
    const std::vector<Field> rows = Elements();
    if (rows.size() != size) Fail("must have " + std::to_string(size) + " rows, one per parameter");
    Eigen::MatrixXd out(size, size);
    for (std::size_t r = 0; r < size; ++r) {
      const std::vector<double> row = rows[r].NumbersOrNaN();
      if (row.size() != size) rows[r].Fail("must have " + std::to_string(size) + " columns, one per parameter");
      for (std::size_t c = 0; c < size; ++c) out(r, c) = row[c];
    }
    return out;
  }

 private:
  void RequireObject() const {
    if (!json_->is_object()) Fail(std::string("must be an object (it is ") + json_->type_name() + ")");
  }

  const Json* json_;
  std::string path_;
  const std::string* source_;
};

ResultModel ReadModel(const Field& m) {
  ResultModel out;
  if (m.Has("kind")) out.kind = m["kind"].String();  // files from before `--model ms` are hb
  try {
    FindModelFamily(out.kind);
  } catch (const InputError&) {
    m["kind"].Fail("is '" + out.kind + "': unknown model (" + ModelFamilyNames() + ")");
  }
  out.law = m["law"].String();
  const Field b = m["beam"];
  out.beam = {.length_m = b["length_m"].Number(),
              .width_m = b["width_m"].Number(),
              .thickness_m = b["thickness_m"].Number(),
              .youngs_modulus_Pa = b["youngs_modulus_Pa"].Number(),
              .density_kg_m3 = b["density_kg_m3"].Number(),
              .loss_factor = b.Has("loss_factor") ? b["loss_factor"].Number() : 0.0};
  try {
    out.beam.Validate();
  } catch (const std::invalid_argument& e) {
    b.Fail(std::string("is not a beam's (") + e.what() + ")");
  }
  out.force_position_m = m["force_position_m"].Number();
  for (const Field& mass : m["sensor_masses"].Elements())
    out.sensor_masses.push_back({.position_m = mass["position_m"].Number(), .mass_kg = mass["mass_kg"].Number()});
  out.fit_channels = m["fit_channels"].Strings();
  // The ranges identify takes (-H 1..50, --fit-harmonics 1..H).
  out.num_harmonics = m["num_harmonics"].Integer();
  if (out.num_harmonics < 1 || out.num_harmonics > 50) m["num_harmonics"].Fail("must lie in 1..50");
  out.num_fit_harmonics = m["num_fit_harmonics"].Integer();
  if (out.num_fit_harmonics < 1 || out.num_fit_harmonics > out.num_harmonics)
    m["num_fit_harmonics"].Fail("must lie in 1..num_harmonics (" + std::to_string(out.num_harmonics) + ")");
  return out;
}

std::vector<ResultParameter> ReadParameters(const Field& root) {
  const std::vector<std::string> order = root["parameter_order"].Strings();
  const Field parameters = root["parameters"];
  if (parameters.Members().size() != order.size())
    parameters.Fail("holds " + std::to_string(parameters.Size()) + " parameters but parameter_order names " +
                    std::to_string(order.size()));
  std::vector<ResultParameter> out;
  for (const auto& name : order) {
    const Field p = parameters[name];
    const std::vector<double> ci95 = p["ci95"].NumbersOrNaN();
    if (ci95.size() != 2) p["ci95"].Fail("must be [low, high]");
    out.push_back({.name = name,
                   .unit = p["unit"].String(),
                   .value = p["value"].Number(),
                   .std = p["std"].NumberOrNaN(),
                   .lower_95 = ci95[0],
                   .upper_95 = ci95[1]});
  }
  return out;
}

ResultFit ReadFit(const Field& f) {
  ResultFit out;
  out.chi_square = f["chi_square"].NumberOrNaN();
  out.degrees_of_freedom = f["degrees_of_freedom"].Integer();
  out.reduced_chi_square = f["reduced_chi_square"].NumberOrNaN();
  out.seconds = f["seconds"].Number();
  for (const Field& s : f["starts"].Elements()) {
    const std::string seeded = s["states_seeded"].String();
    if (seeded != "measured" && seeded != "feasible") s["states_seeded"].Fail("must be \"measured\" or \"feasible\"");
    out.starts.push_back({.start = s["start"].NumbersOrNaN(),
                          .parameters = s["parameters"].NumbersOrNaN(),
                          .objective = s["objective"].NumberOrNaN(),
                          .converged = s["converged"].Boolean(),
                          .iterations = s["iterations"].Integer(),
                          .status = s["status"].String(),
                          .states_seeded = seeded == "measured" ? StartRoute::kMeasuredStates : StartRoute::kFeasibleStates,
                          .branch_repairs = s["branch_repairs"].Integer()});
  }
  out.best_start = f["best_start"].Integer();
  if (out.best_start < 0 || out.best_start >= static_cast<int>(std::max<std::size_t>(out.starts.size(), 1)))
    f["best_start"].Fail("must be the index of one of fit.starts");
  out.starts_at_best = f["starts_at_best"].Integer();
  for (const Field& m : f["minima"].Elements())
    out.minima.push_back({.parameters = m["parameters"].NumbersOrNaN(),
                          .chi_square = m["chi_square"].NumberOrNaN(),
                          .num_starts = m["starts"].Integer()});
  out.second_minimum_chi_square_gap = f["second_minimum_chi_square_gap"].NumberOrNaN();
  out.minimum_decisive = f["minimum_decisive"].Boolean();
  const Field d = f["direct_estimate"];
  out.direct_estimate = {.k1_Nm_rad = d["k1"].NumberOrNaN(),
                         .k2_Nm_rad2 = d["k2"].NumberOrNaN(),
                         .k3_Nm_rad3 = d["k3"].NumberOrNaN(),
                         .c_Nms_rad = d["c"].NumberOrNaN(),
                         .relative_residual = d["relative_residual"].NumberOrNaN()};
  return out;
}

std::vector<ChannelQuality> ReadQuality(const Field& quality, int num_fit_harmonics) {
  std::vector<ChannelQuality> out;
  for (const auto& [channel, per_harmonic] : quality.Members()) {
    ChannelQuality q{.channel = channel};
    for (int k = 0; k < num_fit_harmonics; ++k) {
      std::vector<LevelQuality> per_level;
      for (const auto& [level, entry] : per_harmonic[HarmonicKey(k)].Members())
        per_level.push_back({.level = level,
                             .relative_rms_error = entry["relative_rms_error"].NumberOrNaN(),
                             .chi_square = entry["chi_square"].NumberOrNaN(),
                             .num_steps = entry["steps"].Integer()});
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
                           .position_m = v["position_m"].Number(),
                           .worst_h1_relative_error = v["worst_h1_relative_error"].NumberOrNaN(),
                           .worst_h3_relative_error = v["worst_h3_relative_error"].NumberOrNaN(),
                           .measurable_relative_std = v["measurable_relative_std"].Number(),
                           .measurable_steps_h1 = v["measurable_steps_h1"].Integer(),
                           .measurable_steps_h3 = v["measurable_steps_h3"].Integer()};
    for (const Field& s : v["steps"].Elements()) {
      HeldOutStep step{.level = s["level"].String(), .file = s["file"].String(), .frequency_hz = s["frequency_Hz"].Number()};
      for (int k = 0; k < num_fit_harmonics; ++k) {
        const std::string h = HarmonicKey(k);
        step.harmonics.push_back({.relative_error = s[h + "_relative_error"].NumberOrNaN(),
                                  .measured_relative_std = s[h + "_measured_relative_std"].NumberOrNaN(),
                                  .predicted = s[h + "_predicted"].Phasor(true),
                                  .measured = s[h + "_measured"].Phasor(true)});
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
    ResultStep step{.level = s["level"].String(),
                    .file = s["file"].String(),
                    .frequency_hz = s["frequency_Hz"].Number(),
                    .force_N = s["force_N"].Phasors()};
    const Field state = s[family.StateName()];
    step.state = state.Phasors();
    // A model is driven by the force's fundamental at least.
    if (step.state.size() != state_size || step.force_N.size() < 2)
      state.Fail("must hold " + std::to_string(state_size) + " phasor(s) for a " + family.Description() + " model of " +
                 std::to_string(model.num_harmonics) + " harmonics, and force_N the fundamental (step " + step.file + ")");
    out.push_back(std::move(step));
  }
  return out;
}

ResultFile ReadResult(const Json& root, const std::string& source) {
  if (!root.is_object() || !root.contains("format") || root["format"] != std::string(kResultFormat))
    throw InputError(source + ": not a beamid result (format must be beamid-result/1). Fix: give the result.json "
                     "that 'beamid identify' wrote");
  const Field r(root, "", source);
  ResultFile out;
  if (r.Has("beamid_version")) out.beamid_version = r["beamid_version"].String();
  const Field campaign = r["campaign"];
  out.campaign.folder = campaign["folder"].String();
  out.campaign.name = campaign["name"].String();
  if (campaign.Has("absolute_folder")) out.campaign.absolute_folder = campaign["absolute_folder"].String();
  out.model = ReadModel(r["model"]);
  out.parameters = ReadParameters(r);
  out.linear_parameters = r["linear_parameters"].Strings();
  out.covariance = r["covariance"].SquareMatrix(out.parameters.size());
  out.correlation = r["correlation"].SquareMatrix(out.parameters.size());
  out.fit = ReadFit(r["fit"]);
  out.warnings = r["warnings"].Strings();
  out.quality = ReadQuality(r["quality"], out.model.num_fit_harmonics);
  if (r.Has("validation")) out.validation = ReadValidation(r["validation"], out.model.num_fit_harmonics);
  out.steps = ReadSteps(r["steps"], out.model);
  return out;
}

}  // namespace

std::string ResultFileToJson(const ResultFile& result) {
  Json root = {{"format", std::string(kResultFormat)}};
  if (!result.beamid_version.empty()) root["beamid_version"] = result.beamid_version;
  root["command"] = "identify";
  root["campaign"] = {{"folder", result.campaign.folder}, {"name", result.campaign.name}};
  if (!result.campaign.absolute_folder.empty()) root["campaign"]["absolute_folder"] = result.campaign.absolute_folder;
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
  root["warnings"] = Json(result.warnings);
  root["quality"] = QualityJson(result.quality);
  if (!result.validation.empty()) root["validation"] = ValidationJson(result.validation);
  root["steps"] = StepsJson(result.steps, FindModelFamily(result.model.kind));
  return root.dump(1) + "\n";
}

ResultFile ResultFileFromJson(const std::string& text, const std::string& source) {
  Json root;
  try {
    root = Json::parse(text);
  } catch (const Json::exception& e) {  // syntax, and numbers beyond double (1e400)
    throw InputError(source + ": not valid JSON (" + e.what() + "). Fix: " + kFix);
  }
  return ReadResult(root, source);
}

void WriteResultFile(const std::filesystem::path& file, const ResultFile& result) {
  WriteTextFileAtomically(file, ResultFileToJson(result));
}

ResultFile ReadResultFile(const std::filesystem::path& file) {
  return ResultFileFromJson(
      ReadTextFile(file, "result file", "give the result.json of 'beamid identify', or check the path"), file.string());
}

}  // namespace beamid::solver
