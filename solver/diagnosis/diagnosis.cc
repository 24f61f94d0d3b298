#include "solver/diagnosis/diagnosis.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>
#include <thread>

#include <fmt/core.h>

#include "solver/estimation/chi_square.h"
#include "solver/estimation/identification_problem.h"
#include "solver/estimation/internal/worker_processes.h"

namespace beamid::solver {
namespace {

using Complex = std::complex<double>;

ModelStructure BaseStructure(const DiagnosisOptions& options) {
  ModelStructure structure = PolynomialModel({.k1_Nm_rad = 100.0});
  if (options.fit_loss_factor) structure.linear.push_back(LossFactor(options.loss_factor_start));
  return structure;
}

// A fitted model, rebuilt in this process: its problem with the internal
// scales of the winning start, and the optimiser's variables there.
struct FittedModel {
  ModelStructure structure;
  std::unique_ptr<IdentificationProblem> problem;
  Eigen::VectorXd x;
  int model_harmonics = 5;

  FittedModel(const FitData& fit, const ModelStructure& s, int harmonics, const std::vector<double>& start,
              Eigen::VectorXd variables)
      : structure(s), x(std::move(variables)), model_harmonics(harmonics) {
    problem = std::make_unique<IdentificationProblem>(fit, structure, IdentificationProblemOptions{.num_harmonics = harmonics});
    problem->FeasiblePoint(start);
  }

  // Per step, channels × K phasors of `data`'s channels in its units
  // (harmonics the model lacks are 0).
  std::vector<Eigen::MatrixXcd> Phasors(const FitData& data) const {
    std::vector<double> positions;
    for (const auto& c : data.channels) positions.push_back(c.position_m);
    std::vector<Eigen::MatrixXcd> out;
    const int k_max = data.num_fit_harmonics;
    for (int i = 0; i < static_cast<int>(data.steps.size()); ++i) {
      const Eigen::MatrixXcd y = problem->DisplacementPhasors(x, i, positions);
      Eigen::MatrixXcd m = Eigen::MatrixXcd::Zero(static_cast<Eigen::Index>(positions.size()), k_max);
      for (int c = 0; c < static_cast<int>(positions.size()); ++c)
        for (int k = 1; k <= std::min(k_max, model_harmonics); ++k)
          m(c, k - 1) = DerivativeFactor(data.channels[c].derivative_order, k * data.steps[i].omega_rad_s) * y(c, k);
      out.push_back(m);
    }
    return out;
  }
};

void FillHeldOut(const FittedModel& model, const FitData& validation, FitSummary* summary) {
  if (validation.channels.empty()) return;
  const std::vector<Eigen::MatrixXcd> predicted = model.Phasors(validation);
  double chi2 = 0.0, error2 = 0.0, norm2 = 0.0;
  for (std::size_t i = 0; i < validation.steps.size(); ++i) {
    const FitStep& s = validation.steps[i];
    for (int c = 0; c < static_cast<int>(validation.channels.size()); ++c) {
      for (int k = 1; k <= validation.num_fit_harmonics; ++k) {
        const Complex e = predicted[i](c, k - 1) - s.measured(c, k - 1);
        chi2 += (s.whitening[c][k - 1] * Eigen::Vector2d(e.real(), e.imag())).squaredNorm();
      }
      error2 += std::norm(predicted[i](c, 0) - s.measured(c, 0));
      norm2 += std::norm(s.measured(c, 0));
    }
  }
  summary->held_out_chi_square = chi2;
  summary->held_out_h1_relative_error = std::sqrt(error2 / std::max(norm2, 1e-300));
}

FitSummary Summarize(const ModelStructure& structure, int harmonics, double chi2, int num_residuals,
                     const std::vector<double>& values, const std::vector<double>& std) {
  FitSummary s;
  s.model_harmonics = harmonics;
  const auto names = structure.Names();
  const auto units = structure.Units();
  for (std::size_t j = 0; j < values.size(); ++j)
    s.parameters.push_back({.name = names[j], .unit = units[j], .value = values[j], .std = std[j],
                            .lower_95 = values[j] - 1.96 * std[j], .upper_95 = values[j] + 1.96 * std[j]});
  const int p = static_cast<int>(values.size());
  s.chi_square = chi2;
  s.num_residuals = num_residuals;
  s.degrees_of_freedom = std::max(1, num_residuals - p);
  s.reduced_chi_square = chi2 / s.degrees_of_freedom;
  s.aic = chi2 + 2.0 * p;
  s.bic = chi2 + p * std::log(static_cast<double>(std::max(num_residuals, 1)));
  return s;
}

// One refit job: a candidate from one start.
struct Job {
  int candidate = 0;
  std::vector<double> start;
};


std::string DescribeParameters(const FitSummary& fit, const std::vector<std::string>& names) {
  std::string text;
  for (const auto& p : fit.parameters)
    if (std::find(names.begin(), names.end(), p.name) != names.end())
      text += (text.empty() ? "" : ", ") +
              fmt::format("{} = {:.4g} ± {:.2g} {} (95 %: {:.4g} … {:.4g})", p.name, p.value, 1.96 * p.std, p.unit,
                          p.lower_95, p.upper_95);
  return text;
}

std::string WriteSummary(const DiagnosisResult& r) {
  std::ostringstream out;
  out << fmt::format("Base model (polynomial support on the nominal beam): reduced chi-square {:.3g} over {} residuals. ",
                     r.base.reduced_chi_square, r.base.num_residuals);
  if (r.location)
    for (const auto& f : r.location->findings) out << f << (f.empty() || f.back() == '.' ? " " : ". ");
  if (r.verdict == "cause named") {
    const CandidateOutcome& best = r.candidates.front();
    out << fmt::format(
        "Missing physics: {} ({}). Refitted with it, the weighted residual drops {:.3g}x (chi-square {:.4g} -> {:.4g}, "
        "BIC {:.4g} -> {:.4g}, likelihood-ratio p = {:.2g}). ",
        best.name, best.description, best.residual_drop, r.base.chi_square, best.fit.chi_square, r.base.bic,
        best.fit.bic, best.p_value);
    if (std::isfinite(r.base.held_out_h1_relative_error))
      out << fmt::format("Held-out channels: first-harmonic error {:.3g} % -> {:.3g} %, chi-square of the harmonics "
                         "the model predicts {:.4g} -> {:.4g}. ",
                         100.0 * r.base.held_out_h1_relative_error, 100.0 * r.final_fit.held_out_h1_relative_error,
                         r.base.held_out_chi_square, r.final_fit.held_out_chi_square);
    out << "Identified: " << DescribeParameters(r.final_fit, r.final_extra_parameters) << ".";
  } else if (r.verdict == "unexplained") {
    out << "No candidate explains the misfit significantly: unexplained";
    if (r.location && !r.location->findings.empty()) out << " (see the location above)";
    out << ".";
  } else {
    out << "No significant discrepancy: the base model fits within the noise and no candidate improves it "
           "significantly.";
  }
  return out.str();
}

// The base model in two stages: the polynomial support alone from the
// direct estimate (robust even when the misfit is large), then with the
// beam's loss factor from there. A large misfit can stall the second stage
// (the loss factor runs to its bound); the base is then the first.
IdentifyResult FitBase(const FitData& fit, const DiagnosisOptions& options, const IdentifyOptions& identify,
                       ModelStructure* structure) {
  DiagnosisOptions without = options;
  without.fit_loss_factor = false;
  *structure = BaseStructure(without);
  IdentifyResult polynomial = Identify(fit, *structure, identify);
  if (!options.fit_loss_factor) return polynomial;
  ModelStructure with_loss = BaseStructure(options);
  std::vector<double> first;
  for (const auto& p : polynomial.parameters) first.push_back(p.value);
  first.push_back(options.loss_factor_start);
  try {
    IdentifyResult full = IdentifyWith(
        [&] { return std::make_unique<IdentificationProblem>(fit, with_loss, identify.model); }, with_loss, first,
        identify);
    if (full.chi_square <= polynomial.chi_square) {
      *structure = with_loss;
      return full;
    }
  } catch (const std::runtime_error&) {
  }
  return polynomial;
}

}  // namespace

DiagnosisResult Diagnose(const FitData& fit, const FitData& validation, const FitData& located_in,
                         const DiagnosisOptions& options, const DiagnosisProgress& progress) {
  const auto started = std::chrono::steady_clock::now();
  auto report = [&](double fraction, const std::string& what) {
    if (progress) progress(fraction, what);
  };
  DiagnosisResult result;

  // 1. The base model.
  report(0.0, "base fit");
  IdentifyOptions identify;
  identify.model.num_harmonics = options.model_harmonics;
  identify.ipopt = options.ipopt;
  identify.num_threads = 1;
  ModelStructure base_structure;
  const IdentifyResult base_fit = FitBase(fit, options, identify, &base_structure);
  std::vector<double> base_values, base_std;
  for (const auto& p : base_fit.parameters) {
    base_values.push_back(p.value);
    base_std.push_back(p.std);
  }
  ModelStructure fitted_base = base_structure;
  fitted_base.SetValues(base_values);
  const FittedModel base_model(fit, base_structure, options.model_harmonics,
                               base_fit.starts[base_fit.best_start].scaled_at, base_fit.x);
  result.base = Summarize(base_structure, options.model_harmonics, base_fit.chi_square, fit.NumResiduals(), base_values,
                          base_std);
  FillHeldOut(base_model, validation, &result.base);

  // 2. Where the base misses.
  report(0.15, "locating the misfit");
  const FitData& located = located_in.channels.empty() ? fit : located_in;
  try {
    hb::LinearBeamModel reference = fitted_base.ApplyLinear({.beam = fit.beam, .attachments = fit.sensor_masses});
    const auto& k = dynamic_cast<const hb::PolynomialSupportLaw&>(*fitted_base.law).coefficients();
    reference.support_stiffness_Nm_rad = k.k1_Nm_rad;
    reference.support_damping_Nms_rad = k.c_Nms_rad;
    result.location = LocateMisfit(located, base_model.Phasors(located), fit.num_fit_harmonics, reference,
                                   {.num_fitted_parameters = static_cast<int>(base_values.size())});
  } catch (const std::exception& e) {
    result.location_error = e.what();
  }

  // 3. Every candidate from the base optimum, all starts in parallel.
  BaseFitContext context{.data = &fit, .model_harmonics = options.model_harmonics};
  for (int i = 0; i < base_model.problem->num_steps(); ++i)
    context.theta_amplitude_rad.push_back(
        std::abs(hb::HarmonicBalance::ToComplex(base_model.problem->States(base_model.x, i))[1]));
  std::vector<CandidatePhysics> library;
  for (auto& c : CandidateLibrary())
    if (options.candidates.empty() ||
        std::find(options.candidates.begin(), options.candidates.end(), c.name) != options.candidates.end())
      library.push_back(std::move(c));
  std::vector<CandidateExtension> extensions;
  std::vector<Job> jobs;
  for (int c = 0; c < static_cast<int>(library.size()); ++c) {
    extensions.push_back(library[c].extend(fitted_base, context));
    for (const auto& start : extensions.back().starts) jobs.push_back({c, start});
  }
  struct JobOutcome {
    bool ok = false;
    std::string error;
    double chi2 = 0.0;
    double seconds = 0.0;
    std::vector<double> values, std;
    std::vector<double> scaled_at;  // the parameters whose FeasiblePoint set x's scales
    Eigen::VectorXd x;
  };
  std::vector<JobOutcome> outcomes(jobs.size());
  const int workers = options.num_workers > 0 ? options.num_workers
                                              : std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
  internal::RunInWorkers(
      static_cast<int>(jobs.size()), std::min<int>(workers, static_cast<int>(jobs.size())),
      [&](int j) {
        const CandidateExtension& extension = extensions[jobs[j].candidate];
        IdentifyOptions refit = identify;
        refit.model.num_harmonics = extension.model_harmonics;
        refit.ipopt.max_iterations = options.refit_max_iterations;
        refit.ipopt.max_cpu_seconds = options.refit_max_cpu_seconds;
        // A refit starts from the base fit, whose states already lie on the
        // measured branch; seeded states converge slowly with the
        // candidates' non-smooth laws (measured: 3x the diagnosis's time).
        // Branch repair stays on.
        refit.seed_states_from_measurements = false;
        const IdentifyResult r = IdentifyWith(
            [&] { return std::make_unique<IdentificationProblem>(fit, extension.structure, refit.model); },
            extension.structure, jobs[j].start, refit);
        std::vector<double> record = {r.chi_square, r.seconds};
        for (const auto& p : r.parameters) record.push_back(p.value);
        for (const auto& p : r.parameters) record.push_back(p.std);
        const std::vector<double>& scaled_at = r.starts[r.best_start].scaled_at;
        record.insert(record.end(), scaled_at.begin(), scaled_at.end());
        record.insert(record.end(), r.x.data(), r.x.data() + r.x.size());
        return record;
      },
      [&](int j, const std::vector<double>& record, const std::string& error, int done) {
        JobOutcome& o = outcomes[j];
        if (!error.empty()) {
          o.error = error;
        } else {
          const int p = extensions[jobs[j].candidate].structure.NumParameters();
          o.ok = true;
          o.chi2 = record[0];
          o.seconds = record[1];
          o.values.assign(record.begin() + 2, record.begin() + 2 + p);
          o.std.assign(record.begin() + 2 + p, record.begin() + 2 + 2 * p);
          o.scaled_at.assign(record.begin() + 2 + 2 * p, record.begin() + 2 + 3 * p);
          o.x = Eigen::Map<const Eigen::VectorXd>(record.data() + 2 + 3 * p,
                                                  static_cast<Eigen::Index>(record.size()) - 2 - 3 * p);
        }
        report(0.2 + 0.7 * done / static_cast<double>(jobs.size()),
               "refit " + std::to_string(done) + "/" + std::to_string(jobs.size()) + " (" +
                   library[jobs[j].candidate].name + ")");
      });

  // 4. Each candidate's best start, its test against the base, and the ranking.
  std::vector<int> best_job(library.size(), -1);
  for (int j = 0; j < static_cast<int>(jobs.size()); ++j) {
    const int c = jobs[j].candidate;
    if (outcomes[j].ok && (best_job[c] < 0 || outcomes[j].chi2 < outcomes[best_job[c]].chi2)) best_job[c] = j;
  }
  const double per_candidate_significance = options.significance / std::max<std::size_t>(1, library.size());
  // What a candidate is tested against: the base, or, for one balanced with
  // more harmonics, the better of the base and the converged refit with no
  // parameters of its own at those harmonics (else the harmonics' gain on a
  // truncated base would be credited to its parameters).
  auto reference_chi2 = [&](int c) {
    double reference = result.base.chi_square;
    if (extensions[c].model_harmonics == options.model_harmonics || extensions[c].extra_parameters.empty())
      return reference;
    for (int t = 0; t < static_cast<int>(library.size()); ++t)
      if (extensions[t].extra_parameters.empty() && extensions[t].model_harmonics == extensions[c].model_harmonics &&
          best_job[t] >= 0)
        reference = std::min(reference, outcomes[best_job[t]].chi2);
    return reference;
  };
  std::vector<std::unique_ptr<FittedModel>> fitted(library.size());
  for (int c = 0; c < static_cast<int>(library.size()); ++c) {
    CandidateOutcome outcome;
    outcome.name = library[c].name;
    outcome.description = library[c].description;
    outcome.extra_parameters = extensions[c].extra_parameters;
    outcome.test_dof = extensions[c].test_dof;
    if (result.location) outcome.signature_score = library[c].signature(*result.location);
    for (int k = 0; k < static_cast<int>(jobs.size()); ++k)
      if (jobs[k].candidate == c) outcome.seconds += outcomes[k].seconds;
    const int j = best_job[c];
    if (j < 0) {
      outcome.status = "failed";
      for (int k = 0; k < static_cast<int>(jobs.size()); ++k)
        if (jobs[k].candidate == c && !outcomes[k].error.empty()) outcome.status = "failed: " + outcomes[k].error;
    } else {
      const JobOutcome& o = outcomes[j];
      outcome.converged = true;
      outcome.status = "solved";
      outcome.fit = Summarize(extensions[c].structure, extensions[c].model_harmonics, o.chi2, fit.NumResiduals(),
                              o.values, o.std);
      fitted[c] = std::make_unique<FittedModel>(fit, extensions[c].structure, extensions[c].model_harmonics,
                                                o.scaled_at, o.x);
      fitted[c]->structure.SetValues(o.values);
      FillHeldOut(*fitted[c], validation, &outcome.fit);
      const double scale = std::max(1.0, outcome.fit.reduced_chi_square);
      const double reference = reference_chi2(c);
      outcome.likelihood_ratio = (reference - o.chi2) / scale;
      outcome.p_value = ChiSquareUpperTail(outcome.likelihood_ratio, outcome.test_dof);
      outcome.residual_drop = result.base.chi_square / std::max(o.chi2, 1e-300);
      // A base that already fits within the model's own errors has nothing
      // to explain: a flexible candidate can still shave a share of its χ²
      // (measured: a Jenkins element took 38 % off one of ten base-physics
      // noise realisations), which is not a cause.
      outcome.significant = outcome.p_value < per_candidate_significance &&
                            reference - o.chi2 >= options.min_relative_improvement * reference &&
                            result.base.reduced_chi_square > options.acceptable_reduced_chi_square;
    }
    result.candidates.push_back(std::move(outcome));
  }
  std::vector<int> order(library.size());
  for (int c = 0; c < static_cast<int>(order.size()); ++c) order[c] = c;
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) {
    const CandidateOutcome &x = result.candidates[a], &y = result.candidates[b];
    if (x.significant != y.significant) return x.significant;
    if (x.converged != y.converged) return x.converged;
    if (x.converged && x.fit.bic != y.fit.bic) return x.fit.bic < y.fit.bic;
    return x.signature_score > y.signature_score;
  });
  std::vector<CandidateOutcome> ranked;
  for (int c : order) ranked.push_back(result.candidates[c]);
  result.candidates = std::move(ranked);

  // 5. Verdict and the final model.
  const FittedModel* final_model = &base_model;
  if (!result.candidates.empty() && result.candidates.front().significant) {
    result.verdict = "cause named";
    result.selected = {result.candidates.front().name};
    result.final_fit = result.candidates.front().fit;
    result.final_extra_parameters = result.candidates.front().extra_parameters;
    final_model = fitted[order.front()].get();
  } else {
    const bool misfit = result.base.reduced_chi_square > options.acceptable_reduced_chi_square &&
                        (!result.location || result.location->significant);
    result.verdict = misfit ? "unexplained" : "no significant discrepancy";
    result.selected = {"none"};
    result.final_fit = result.base;
  }

  // 6. Response curves of both models against the measurements.
  report(0.95, "response curves");
  for (const FitData* data : {&fit, &validation}) {
    if (data->channels.empty()) continue;
    const auto base_y = base_model.Phasors(*data);
    const auto final_y = final_model->Phasors(*data);
    for (std::size_t i = 0; i < data->steps.size(); ++i)
      for (int c = 0; c < static_cast<int>(data->channels.size()); ++c)
        result.response.push_back({.level = data->steps[i].level,
                                   .frequency_hz = data->steps[i].omega_rad_s / (2.0 * 3.141592653589793),
                                   .channel = data->channels[c].channel,
                                   .held_out = data == &validation,
                                   .measured = data->steps[i].measured(c, 0),
                                   .base_model = base_y[i](c, 0),
                                   .final_model = final_y[i](c, 0)});
  }
  result.summary = WriteSummary(result);
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  report(1.0, "done");
  return result;
}

namespace {

nlohmann::json ToJson(const FitSummary& s) {
  nlohmann::json parameters = nlohmann::json::object();
  for (const auto& p : s.parameters)
    parameters[p.name] = {{"value", p.value}, {"std", p.std}, {"unit", p.unit}, {"ci95", {p.lower_95, p.upper_95}}};
  auto number = [](double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); };
  return {{"parameters", parameters},
          {"model_harmonics", s.model_harmonics},
          {"chi_square", s.chi_square},
          {"degrees_of_freedom", s.degrees_of_freedom},
          {"num_residuals", s.num_residuals},
          {"reduced_chi_square", s.reduced_chi_square},
          {"aic", s.aic},
          {"bic", s.bic},
          {"held_out_chi_square", number(s.held_out_chi_square)},
          {"held_out_h1_relative_error", number(s.held_out_h1_relative_error)}};
}

}  // namespace

nlohmann::json ToJson(const DiagnosisResult& r) {
  nlohmann::json candidates = nlohmann::json::array();
  for (const auto& c : r.candidates) {
    nlohmann::json extra = nlohmann::json::object();
    for (const auto& p : c.fit.parameters)
      if (std::find(c.extra_parameters.begin(), c.extra_parameters.end(), p.name) != c.extra_parameters.end())
        extra[p.name] = {{"value", p.value}, {"std", p.std}, {"unit", p.unit}, {"ci95", {p.lower_95, p.upper_95}}};
    candidates.push_back({{"name", c.name},
                          {"description", c.description},
                          {"score", c.signature_score},
                          {"converged", c.converged},
                          {"status", c.status},
                          {"significant", c.significant},
                          {"extra_parameters", extra},
                          {"residual_before", r.base.chi_square},
                          {"residual_after", c.converged ? nlohmann::json(c.fit.chi_square) : nlohmann::json(nullptr)},
                          {"residual_drop", c.residual_drop},
                          {"likelihood_ratio", c.likelihood_ratio},
                          {"test_dof", c.test_dof},
                          {"p_value", c.p_value},
                          {"seconds", c.seconds},
                          {"fit", ToJson(c.fit)}});
  }
  nlohmann::json location = r.location ? ToJson(*r.location) : nlohmann::json{{"error", r.location_error}};
  return {{"format", "beamid-diagnosis/1"},
          {"selected", r.selected},
          {"verdict", r.verdict},
          {"summary", r.summary},
          {"base", ToJson(r.base)},
          {"final", {{"extension", r.selected}, {"fit", ToJson(r.final_fit)}}},
          {"candidates", candidates},
          {"location", location},
          {"seconds", r.seconds}};
}

std::string ResponseCsv(const DiagnosisResult& r) {
  std::ostringstream out;
  out << "level,frequency_Hz,channel,held_out,measured_amp,measured_phase_rad,base_amp,base_phase_rad,final_amp,"
         "final_phase_rad\n";
  for (const auto& p : r.response)
    out << fmt::format("{},{:.6f},{},{},{:.8g},{:.6f},{:.8g},{:.6f},{:.8g},{:.6f}\n", p.level, p.frequency_hz,
                       p.channel, p.held_out ? 1 : 0, std::abs(p.measured), std::arg(p.measured),
                       std::abs(p.base_model), std::arg(p.base_model), std::abs(p.final_model),
                       std::arg(p.final_model));
  return out.str();
}

}  // namespace beamid::solver
