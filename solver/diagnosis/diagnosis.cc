#include "solver/diagnosis/diagnosis.h"
#include "solver/diagnosis/measurement_artefacts.h"

#include "hb/option_checks.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>
#include <thread>

#include <fmt/core.h>

#include "hb/errors.h"
#include "solver/diagnosis/diagnosis_io.h"
#include "solver/estimation/chi_square.h"
#include "solver/estimation/model_phasors.h"
#include "solver/estimation/internal/worker_processes.h"
#include "solver/estimation/whitened_misfit.h"

namespace beamid::solver {
namespace {

using Complex = std::complex<double>;

ModelStructure BaseStructure(const DiagnosisOptions& options) {
  ModelStructure structure = PolynomialModel({.k1_Nm_rad = 100.0});
  if (options.fit_loss_factor) structure.linear.push_back(BeamLossFactor(options));
  return structure;
}

}  // namespace

LinearParameter BeamLossFactor(const DiagnosisOptions& options) {
  return options.modal_loss_factor ? ModalLossFactor(options.loss_factor_start) : LossFactor(options.loss_factor_start);
}

FitSummary SummarizeFit(const ModelStructure& structure, int harmonics, double chi2, int num_residuals,
                        const std::vector<double>& values, const std::vector<double>& std, int extra_parameters) {
  FitSummary s;
  s.model_harmonics = harmonics;
  const auto names = structure.Names();
  const auto units = structure.Units();
  for (std::size_t j = 0; j < values.size(); ++j)
    s.parameters.push_back({.name = names[j], .unit = units[j], .value = values[j], .std = std[j],
                            .lower_95 = values[j] - 1.96 * std[j], .upper_95 = values[j] + 1.96 * std[j]});
  const int p = static_cast<int>(values.size()) + extra_parameters;
  s.chi_square = chi2;
  s.num_residuals = num_residuals;
  s.degrees_of_freedom = std::max(1, num_residuals - p);
  s.reduced_chi_square = chi2 / s.degrees_of_freedom;
  s.aic = chi2 + 2.0 * p;
  s.bic = chi2 + p * std::log(static_cast<double>(std::max(num_residuals, 1)));
  return s;
}

IdentifyOptions CandidateRefitOptions(const DiagnosisOptions& options, int model_harmonics) {
  IdentifyOptions refit;
  refit.model.num_harmonics = model_harmonics;
  refit.ipopt = options.ipopt;
  refit.family = options.family;
  refit.num_workers = 1;
  refit.ipopt.max_iterations = options.refit_max_iterations;
  refit.first_start_min_iterations = 0;
  refit.continuation_iterations = 0;  // a refit that wanders is cut short on purpose
  // A refit starts from the base fit, whose states already lie on the
  // measured branch; seeded states converge slowly with the
  // candidates' non-smooth laws (measured: 3x the diagnosis's time).
  // Branch repair stays on.
  refit.seed_states_from_measurements = false;
  return refit;
}

void TestAgainstReference(double reference, const FitSummary& base, int num_candidates, const DiagnosisOptions& options,
                          CandidateOutcome* outcome) {
  const double chi_square = outcome->fit.chi_square;
  const double per_candidate_significance = options.significance / std::max(1, num_candidates);
  const double scale = std::max(1.0, outcome->fit.reduced_chi_square);
  outcome->likelihood_ratio = (reference - chi_square) / scale;
  outcome->p_value = ChiSquareUpperTail(outcome->likelihood_ratio, outcome->test_dof);
  outcome->residual_drop = base.chi_square / std::max(chi_square, 1e-300);
  // No gate on the base's own misfit: one hid every cause behind a base
  // reduced χ² up to 4, whatever the noise (under the relative floor the
  // base of a clean campaign reads 0.03). The test alone holds its rate:
  // measured over 50 base-physics realisations per weighting (docs/diagnose.md).
  outcome->significant = outcome->p_value < per_candidate_significance &&
                         reference - chi_square >= options.min_relative_improvement * reference;
}

namespace {

// The named parameters' values; a cause without parameters of its own (an
// outlying step, more harmonics) shows the support's instead.
std::string DescribeParameters(const FitSummary& fit, const std::vector<std::string>& extra) {
  const std::vector<std::string> names = extra.empty() ? std::vector<std::string>{"k1", "k3", "c"} : extra;
  std::string text;
  for (const auto& p : fit.parameters)
    if (std::find(names.begin(), names.end(), p.name) != names.end())
      text += (text.empty() ? "" : ", ") +
              fmt::format("{} = {:.6g} ± {:.2g} {} (95 %: {:.6g} … {:.6g})", p.name, p.value, 1.96 * p.std, p.unit,
                          p.lower_95, p.upper_95);
  return text;
}

std::string WriteSummary(const DiagnosisResult& r) {
  std::ostringstream out;
  out << fmt::format("Base model (polynomial support on the nominal beam): reduced chi-square {:.3g} over {} residuals. ",
                     r.base.reduced_chi_square, r.base.num_residuals);
  for (const auto& f : r.recording_findings) out << "The extraction flagged: " << f << ". ";
  if (r.location)
    for (const auto& f : r.location->findings) out << f << (f.empty() || f.back() == '.' ? " " : ". ");
  if (r.verdict == DiagnosisVerdict::kCausesIndistinguishable) {
    const CandidateOutcome &a = r.candidates[0], &b = r.candidates[1];
    out << fmt::format(
        "{}: {} or {}; these data cannot tell them apart (chi-square {:.4g} and {:.4g}{}). Both explain "
        "the misfit significantly (chi-square {:.4g} before); the results show the first. ",
        a.measurement && b.measurement   ? "A fault of the recording"
        : a.measurement || b.measurement ? "A fault of the recording or missing physics"
                                         : "Missing physics",
        a.name, b.name, a.fit.chi_square, b.fit.chi_square,
        std::isfinite(a.fit.held_out_chi_square)
            ? fmt::format(", held-out {:.4g} and {:.4g}", a.fit.held_out_chi_square, b.fit.held_out_chi_square)
            : std::string(),
        r.base.chi_square);
    out << "Identified with " << a.name << ": " << DescribeParameters(r.final_fit, r.final_extra_parameters) << ".";
    if (r.suggestion) out << " " << r.suggestion->text;
  } else if (r.verdict == DiagnosisVerdict::kCombinationNamed) {
    const CandidateOutcome& first = r.candidates.front();
    const auto pair = std::find_if(r.combinations.begin(), r.combinations.end(), [&](const CandidateOutcome& c) {
      return c.name == r.selected[0] + " + " + r.selected[1];
    });
    out << fmt::format(
        "Missing physics: {} and {} together. {} alone removes most of the misfit (chi-square {:.4g} -> {:.4g}) but "
        "leaves a reduced chi-square of {:.3g}, beyond the noise; with {} as well it drops to {:.4g} "
        "(likelihood-ratio p = {:.2g} against {} alone){}. ",
        r.selected[0], r.selected[1], r.selected[0], r.base.chi_square, first.fit.chi_square,
        first.fit.reduced_chi_square, r.selected[1], r.final_fit.chi_square,
        pair == r.combinations.end() ? 1.0 : pair->p_value, r.selected[0],
        std::isfinite(r.final_fit.held_out_h1_relative_error)
            ? fmt::format("; held-out first-harmonic error {:.3g} % -> {:.3g} % -> {:.3g} %",
                          100.0 * r.base.held_out_h1_relative_error, 100.0 * first.fit.held_out_h1_relative_error,
                          100.0 * r.final_fit.held_out_h1_relative_error)
            : std::string());
    out << "Identified: " << DescribeParameters(r.final_fit, r.final_extra_parameters) << ".";
  } else if (r.verdict == DiagnosisVerdict::kCauseNamed) {
    const CandidateOutcome& best = r.candidates.front();
    out << fmt::format(
        "{}: {} ({}). Refitted with it, the weighted residual drops {:.3g}x (chi-square {:.4g} -> {:.4g}, "
        "BIC {:.4g} -> {:.4g}, likelihood-ratio p = {:.2g}). ",
        best.measurement ? "A fault of the recording, not of the model" : "Missing physics", best.name,
        best.description, best.residual_drop, r.base.chi_square, best.fit.chi_square, r.base.bic,
        best.fit.bic, best.p_value);
    if (std::isfinite(r.base.held_out_h1_relative_error))
      out << fmt::format("{}: first-harmonic error {:.3g} % -> {:.3g} %, chi-square of the harmonics "
                         "the model predicts {:.4g} -> {:.4g}. ",
                         r.ranked_by == RankedBy::kLevelsLeftOut ? "Levels left out in turn" : "Held-out channels",
                         100.0 * r.base.held_out_h1_relative_error, 100.0 * r.final_fit.held_out_h1_relative_error,
                         r.base.held_out_chi_square, r.final_fit.held_out_chi_square);
    if (r.ranked_by != RankedBy::kInSampleBic && r.candidates.size() > 1 && r.candidates[1].significant &&
        r.candidates[1].fit.bic < best.fit.bic)
      out << fmt::format("The {} decide: {} fits the data it saw better (BIC {:.5g}) but predicts "
                         "what it did not see worse (chi-square {:.4g} against {:.4g}). ",
                         ToString(r.ranked_by), r.candidates[1].name, r.candidates[1].fit.bic,
                         r.candidates[1].fit.held_out_chi_square,
                         best.fit.held_out_chi_square);
    out << "Identified: " << DescribeParameters(r.final_fit, r.final_extra_parameters) << ".";
  } else if (r.verdict == DiagnosisVerdict::kUnexplained) {
    out << "No candidate explains the misfit significantly: unexplained";
    if (r.location && !r.location->findings.empty()) out << " (see the location above)";
    out << ".";
  } else {
    out << "No significant discrepancy: the base model fits within the noise and no candidate improves it "
           "significantly.";
  }
  if (r.verdict == DiagnosisVerdict::kCauseNamed || r.verdict == DiagnosisVerdict::kCombinationNamed) {
    std::string checks;
    for (const auto& name : r.selected)
      for (const auto& c : r.candidates)
        if (c.name == name && !c.rig_check.empty()) checks += (checks.empty() ? "" : "; ") + c.rig_check;
    if (!checks.empty()) out << " On the rig: " << checks << ".";
  }
  if (r.verdict == DiagnosisVerdict::kCauseNamed || r.verdict == DiagnosisVerdict::kCausesIndistinguishable ||
      r.verdict == DiagnosisVerdict::kCombinationNamed)
    out << (r.rest_within_noise
                ? fmt::format(" The rest of the misfit lies within the noise (reduced chi-square {:.3g}).",
                              r.final_fit.reduced_chi_square)
                : fmt::format(" This explains only part of the misfit: the reduced chi-square is still {:.3g}, beyond "
                              "the noise; another effect remains.",
                              r.final_fit.reduced_chi_square));
  return out.str();
}

IdentifyOptions BaseIdentifyOptions(const DiagnosisOptions& options) {
  IdentifyOptions identify;
  identify.model.num_harmonics = options.model_harmonics;
  identify.ipopt = options.ipopt;
  identify.family = options.family;
  identify.num_workers = 1;
  return identify;
}

// FitBase's two fits; *structure: the one returned.
IdentifyResult FitPolynomialThenLossFactor(const FitData& fit, const DiagnosisOptions& options,
                                           const IdentifyOptions& identify, ModelStructure* structure) {
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
        [&] { return identify.family->MakeProblem(fit, with_loss, identify.model); }, with_loss, first,
        identify);
    if (full.chi_square <= polynomial.chi_square) {
      *structure = with_loss;
      return full;
    }
  } catch (const std::runtime_error&) {
  }
  return polynomial;
}

// Validated on the levels left out in turn, when there is no held-out
// channel: this many of the significant candidates, best BIC first.
constexpr int kLevelValidatedCandidates = 3;

std::vector<int> BestSignificant(const std::vector<CandidateOutcome>& outcomes, int count) {
  std::vector<int> chosen;
  for (int c = 0; c < static_cast<int>(outcomes.size()); ++c)
    if (outcomes[c].significant && outcomes[c].Refitted()) chosen.push_back(c);
  std::stable_sort(chosen.begin(), chosen.end(),
                   [&](int a, int b) { return outcomes[a].fit.bic < outcomes[b].fit.bic; });
  if (static_cast<int>(chosen.size()) > count) chosen.resize(static_cast<std::size_t>(count));
  return chosen;
}

void ApplyHeldOut(const HeldOutCheck& check, FitSummary* summary) {
  summary->held_out_chi_square = check.chi_square;
  summary->held_out_h1_relative_error = check.h1_relative_error;
  summary->held_out_num_residuals = check.num_residuals;
}

// ---- RefitCandidates' steps ----

// One refit job: a candidate from one start.
struct Job {
  int candidate = 0;
  std::vector<double> start;
};

struct JobOutcome {
  bool ok = false;
  std::string error;
  CandidateRefit refit;
};

// Everything the refits of one diagnosis share.
struct RefitRun {
  std::vector<CandidatePhysics> library;  // the selected candidates
  std::vector<CandidateExtension> extensions;  // [c]
  std::vector<Job> jobs;
  std::vector<JobOutcome> outcomes;  // [job]
  std::vector<int> best_job;         // [c]: its job of least χ², -1 when none converged
};

// What the candidates see of the base fit: the rotation amplitude of every step.
BaseFitContext ContextOf(const FitData& fit, const FittedModel& model) {
  return {.data = &fit,
          .theta_amplitude_rad = model.SupportRotationAmplitudes_rad(),
          .model_harmonics = model.model_harmonics};
}

// The library's candidates that options.candidates selects (all when empty).
std::vector<CandidatePhysics> SelectedCandidates(const DiagnosisOptions& options) {
  std::vector<CandidatePhysics> selected;
  for (auto& c : CandidateLibrary())
    if (options.candidates.empty() ||
        std::find(options.candidates.begin(), options.candidates.end(), c.name) != options.candidates.end())
      selected.push_back(std::move(c));
  return selected;
}

// The workers take the jobs in order: the costliest first (more harmonics,
// then a changed support law, whose non-smooth laws converge slowly), so
// that no long refit starts last and runs alone. Stable: a candidate's
// starts keep their order, and so its best start among equals.
std::pair<int, int> Cost(const CandidateExtension& e) {
  const bool law_changed = dynamic_cast<const hb::CompositeSupportLaw*>(e.structure.law.get()) != nullptr;
  return {e.model_harmonics, law_changed ? 1 : 0};
}

void HeaviestFirst(RefitRun* run) {
  std::stable_sort(run->jobs.begin(), run->jobs.end(), [&](const Job& a, const Job& b) {
    return Cost(run->extensions[a.candidate]) > Cost(run->extensions[b.candidate]);
  });
}

// The beam's loss factor in every refit of physics when the diagnosis fits
// it, tested as one more parameter. The base keeps it only where it lowers
// the base's misfit; a base far from the data (a modulus 5 % off) often drops
// it, and the named model then put the beam's damping in c: 0.05080, 95 %
// within ±0.00001, against 0.05, with no interval over the damping laws.
void WithLossFactor(const DiagnosisOptions& options, CandidateExtension* extension) {
  const auto names = extension->structure.Names();
  const LinearParameter loss = BeamLossFactor(options);
  if (!options.fit_loss_factor || std::find(names.begin(), names.end(), loss.name) != names.end()) return;
  extension->structure.linear.push_back(loss);
  for (auto& start : extension->starts) start.push_back(options.loss_factor_start);
  ++extension->test_dof;
}

// The selected candidates extended from the base optimum, and one job per start.
RefitRun PlanRefits(const FitData& fit, const BaseFit& base, const DiagnosisOptions& options) {
  const BaseFitContext context = ContextOf(fit, base.model);
  RefitRun run;
  run.library = SelectedCandidates(options);
  for (int c = 0; c < static_cast<int>(run.library.size()); ++c) {
    run.extensions.push_back(run.library[c].extend(base.model.structure, context));
    WithLossFactor(options, &run.extensions.back());
    for (const auto& start : run.extensions.back().starts) run.jobs.push_back({c, start});
  }
  HeaviestFirst(&run);
  return run;
}

// Pairs: the named cause's refit extended by each partner, from its optimum
// (a partner that cannot extend it, e.g. a second change of the support law,
// is left out). The pairs' names are "first + partner".
RefitRun PlanPairs(const FitData& fit, const FittedModel& first, const CandidateOutcome& first_outcome,
                   const std::vector<std::string>& partners, const DiagnosisOptions& options) {
  const BaseFitContext context = ContextOf(fit, first);
  RefitRun run;
  for (const CandidatePhysics& partner : SelectedCandidates(options)) {
    if (std::find(partners.begin(), partners.end(), partner.name) == partners.end()) continue;
    CandidateExtension extension;
    try {
      extension = partner.extend(first.structure, context);
    } catch (const std::invalid_argument&) {
      continue;
    }
    extension.model_harmonics = std::max(extension.model_harmonics, first.model_harmonics);
    extension.extra_parameters.insert(extension.extra_parameters.begin(), first_outcome.extra_parameters.begin(),
                                      first_outcome.extra_parameters.end());
    CandidatePhysics pair = partner;
    pair.name = first_outcome.name + " + " + partner.name;
    pair.description = first_outcome.description + "; and " + partner.description;
    pair.rig_check = first_outcome.rig_check + "; and " + partner.rig_check;
    pair.rig_check_for = nullptr;  // the pair's check is the two checks as they stand
    run.library.push_back(std::move(pair));
    run.extensions.push_back(std::move(extension));
    for (const auto& start : run.extensions.back().starts)
      run.jobs.push_back({static_cast<int>(run.library.size()) - 1, start});
  }
  HeaviestFirst(&run);
  return run;
}

// One job, in a worker process: the refit as exact text.
std::string RunRefitJob(const FitData& fit, const CandidateExtension& extension, const std::vector<double>& start,
                        const DiagnosisOptions& options) {
  const IdentifyOptions refit = CandidateRefitOptions(options, extension.model_harmonics);
  const IdentifyResult r = IdentifyWith(
      [&] { return refit.family->MakeProblem(fit, extension.structure, refit.model); },
      extension.structure, start, refit);
  CandidateRefit record{.chi_square = r.chi_square, .seconds = r.seconds};
  for (const auto& p : r.parameters) {
    record.values.push_back(p.value);
    record.std.push_back(p.std);
  }
  record.scaled_at = r.starts[r.best_start].scaled_at;
  record.x.assign(r.x.data(), r.x.data() + r.x.size());
  return CandidateRefitToText(record);
}

// A job's record as the parent reads it back; a record it cannot trust is a failed job.
JobOutcome ReadRefitRecord(const std::string& record, const std::string& error, std::size_t num_parameters) {
  JobOutcome o;
  if (!error.empty()) {
    o.error = error;
    return o;
  }
  try {
    o.refit = CandidateRefitFromText(record);
    if (o.refit.values.size() != num_parameters || o.refit.std.size() != num_parameters ||
        o.refit.scaled_at.size() != num_parameters)
      throw std::runtime_error("a candidate refit's record holds the wrong number of parameters");
    o.ok = true;
  } catch (const std::runtime_error& e) {
    o.error = e.what();
  }
  return o;
}

// Every job in parallel worker processes; then each candidate's best start.
std::vector<int> AllJobs(const RefitRun& run) {
  std::vector<int> all(run.jobs.size());
  for (std::size_t j = 0; j < all.size(); ++j) all[j] = static_cast<int>(j);
  return all;
}

// The jobs `which` in parallel worker processes; then each candidate's best
// start over every job run so far. done_before: jobs run before this batch,
// for the progress.
void RunRefits(const FitData& fit, const DiagnosisOptions& options, const RefitProgress& progress, RefitRun* run,
               const std::vector<int>& which, int done_before = 0) {
  const int num_jobs = static_cast<int>(run->jobs.size());
  if (run->outcomes.size() != run->jobs.size()) run->outcomes.assign(run->jobs.size(), {});
  const int workers = options.num_workers > 0 ? options.num_workers
                                              : std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
  const int batch = static_cast<int>(which.size());
  if (batch > 0) {
    internal::RunTextJobsInWorkers(
        batch, std::min<int>(workers, batch),
        [&](int b) {
          const Job& job = run->jobs[which[b]];
          return RunRefitJob(fit, run->extensions[job.candidate], job.start, options);
        },
        [&](int b, const std::string& record, const std::string& error, int done) {
          const int c = run->jobs[which[b]].candidate;
          run->outcomes[which[b]] = ReadRefitRecord(record, error, run->extensions[c].structure.NumParameters());
          if (progress) progress(done_before + done, num_jobs, run->library[c].name);
        });
  }
  run->best_job.assign(run->library.size(), -1);
  for (int j = 0; j < num_jobs; ++j) {
    const int c = run->jobs[j].candidate;
    const auto& o = run->outcomes;
    if (o[j].ok && (run->best_job[c] < 0 || o[j].refit.chi_square < o[run->best_job[c]].refit.chi_square))
      run->best_job[c] = j;
  }
}

// What candidate c is tested against: the base, or, for one balanced with
// more harmonics, the better of the base and the converged refits with no
// parameters of their own at those harmonics or fewer (else the harmonics'
// gain on a truncated base would be credited to its parameters).
double ReferenceChiSquare(const RefitRun& run, int c, double base_chi_square, int base_harmonics) {
  double reference = base_chi_square;
  const CandidateExtension& e = run.extensions[c];
  if (e.model_harmonics == base_harmonics || e.extra_parameters.empty()) return reference;
  for (int t = 0; t < static_cast<int>(run.library.size()); ++t)
    if (run.extensions[t].extra_parameters.empty() && run.extensions[t].model_harmonics <= e.model_harmonics &&
        run.best_job[t] >= 0)
      reference = std::min(reference, run.outcomes[run.best_job[t]].refit.chi_square);
  return reference;
}

// Candidate c's outcome before its test: what it is, its time, and why it failed.
CandidateOutcome DescribeCandidate(const RefitRun& run, int c, const std::optional<MisfitLocation>& location) {
  CandidateOutcome outcome;
  outcome.name = run.library[c].name;
  outcome.description = run.library[c].description;
  outcome.rig_check = run.library[c].rig_check;
  outcome.extra_parameters = run.extensions[c].extra_parameters;
  outcome.test_dof = run.extensions[c].test_dof;
  if (location) outcome.signature_score = run.library[c].signature(*location);
  for (int k = 0; k < static_cast<int>(run.jobs.size()); ++k)
    if (run.jobs[k].candidate == c) outcome.seconds += run.outcomes[k].refit.seconds;
  if (run.best_job[c] < 0) {
    outcome.status = RefitStatus::kFailed;
    for (int k = 0; k < static_cast<int>(run.jobs.size()); ++k)
      if (run.jobs[k].candidate == c && !run.outcomes[k].error.empty()) outcome.status_message = run.outcomes[k].error;
  }
  return outcome;
}

// Candidate c's best refit, its model, and its likelihood-ratio test (header).
std::unique_ptr<FittedModel> TestCandidate(const FitData& fit, const FitSummary& base, const RefitRun& run, int c,
                                           const DiagnosisOptions& options, int num_candidates,
                                           CandidateOutcome* outcome) {
  const CandidateRefit& o = run.outcomes[run.best_job[c]].refit;
  const CandidateExtension& extension = run.extensions[c];
  outcome->status = RefitStatus::kRefitted;
  outcome->fit =
      SummarizeFit(extension.structure, extension.model_harmonics, o.chi_square, fit.NumResiduals(), o.values, o.std);
  if (run.library[c].rig_check_for) outcome->rig_check = run.library[c].rig_check_for(outcome->fit.parameters);
  auto model = std::make_unique<FittedModel>(
      fit, *options.family, extension.structure, extension.model_harmonics, o.scaled_at,
      Eigen::Map<const Eigen::VectorXd>(o.x.data(), static_cast<Eigen::Index>(o.x.size())), o.values);
  TestAgainstReference(ReferenceChiSquare(run, c, base.chi_square, options.model_harmonics), base,
                       num_candidates > 0 ? num_candidates : static_cast<int>(run.library.size()), options, outcome);
  return model;
}

// Per harmonic 1..K of channel c at a step, |L⁻¹(Y_model − Y_measured)|.
std::vector<double> WhitenedMisfits(const FitStep& step, int c, const Eigen::MatrixXcd& model) {
  std::vector<double> sigma;
  for (int k = 0; k < step.measured.cols(); ++k)
    sigma.push_back(Whitened(step, c, k + 1, model(c, k) - step.measured(c, k)).norm());
  return sigma;
}

// Measured, base and final first harmonics of the fitted and held-out channels.
// final_clock_error: the final model's ε when it is the clock error's (0
// otherwise): it was fitted at the true frequencies, where it gives what the
// channels record at the read ones.
std::vector<ResponsePoint> ResponseCurves(const FitData& fit, const FitData& validation, const FittedModel& base,
                                          const FittedModel& final_model, double final_clock_error) {
  std::vector<ResponsePoint> response;
  for (const FitData* data : {&fit, &validation}) {
    if (data->channels.empty()) continue;
    const auto base_y = base.Phasors(*data);
    // The final model read against the data it was fitted to (a fault of the
    // recording corrected), so that its fitted misfits' squares sum to its χ².
    const FitData final_at =
        data == &fit ? final_model.data
                     : CorrectedData(*data, {.kind = ArtefactKind::kClockError, .value = final_clock_error});
    const auto final_y = final_model.Phasors(final_at);
    for (std::size_t i = 0; i < data->steps.size(); ++i) {
      const FitStep& step = data->steps[i];
      for (int c = 0; c < static_cast<int>(data->channels.size()); ++c)
        response.push_back({.level = step.level,
                            .frequency_hz = step.FrequencyHz(),
                            .channel = data->channels[c].channel,
                            .held_out = data == &validation,
                            .measured = step.measured(c, 0),
                            .base_model = base_y[i](c, 0),
                            .final_model = final_y[i](c, 0),
                            .base_misfit_sigma = WhitenedMisfits(step, c, base_y[i]),
                            .final_misfit_sigma = WhitenedMisfits(final_at.steps[i], c, final_y[i])});
    }
  }
  return response;
}

// The selected model's backbone at the first fitted channel; a failure to
// trace it is kept as the reason, not thrown: the diagnosis stands without it.
SelectedBackbone FinalBackbone(const FittedModel& model, int num_points) {
  const FitChannel& reference = model.data.channels.front();
  SelectedBackbone backbone{.channel = reference.channel, .position_m = reference.position_m};
  try {
    const IdentifiedModel identified = model.Identified();
    backbone.points = model.family->BackboneAtSensor(identified, reference.position_m, num_points);
  } catch (const std::runtime_error& error) {
    backbone.error = error.what();
  }
  return backbone;
}

}  // namespace

void DiagnosisOptions::Validate() const {
  using namespace option_checks;
  RequireInRange("DiagnosisOptions.model_harmonics", model_harmonics, 1, kMaxHarmonics);
  RequireNonNegative("DiagnosisOptions.loss_factor_start", loss_factor_start);
  std::string known;
  for (const auto& c : CandidateLibrary()) known += (known.empty() ? "" : ", ") + c.name;
  for (const auto& name : candidates) {
    const auto library = CandidateLibrary();
    if (std::none_of(library.begin(), library.end(), [&](const auto& c) { return c.name == name; }))
      Refuse("DiagnosisOptions.candidates", "'" + name + "'", "one of " + known);
  }
  if (!(significance > 0.0 && significance < 1.0))
    Refuse("DiagnosisOptions.significance", FormatValue(significance), "in (0, 1)");
  if (!(min_relative_improvement >= 0.0 && min_relative_improvement < 1.0))
    Refuse("DiagnosisOptions.min_relative_improvement", FormatValue(min_relative_improvement), "in [0, 1)");
  RequireNonNegative("DiagnosisOptions.acceptable_reduced_chi_square", acceptable_reduced_chi_square);
  RequireInRange("DiagnosisOptions.num_workers", num_workers, 0, 256);
  if (family == nullptr) Refuse("DiagnosisOptions.family", "null", "a model family (solver/estimation/model_family.h)");
  ipopt.Validate();
  RequireAtLeast("DiagnosisOptions.refit_max_iterations", refit_max_iterations, 1);
  RequireInRange("DiagnosisOptions.max_pair_partners", max_pair_partners, 0, 16);
  RequireInRange("DiagnosisOptions.backbone_points", backbone_points, 2, 1000);
}

BaseFit FitBase(const FitData& fit, const DiagnosisOptions& options) {
  ModelStructure structure;
  const IdentifyResult r = FitPolynomialThenLossFactor(fit, options, BaseIdentifyOptions(options), &structure);
  std::vector<double> values, std;
  for (const auto& p : r.parameters) {
    values.push_back(p.value);
    std.push_back(p.std);
  }
  return {.model = FittedModel(fit, *options.family, structure, options.model_harmonics, r.starts[r.best_start].scaled_at, r.x, values),
          .summary = SummarizeFit(structure, options.model_harmonics, r.chi_square, fit.NumResiduals(), values, std)};
}

HeldOutCheck ValidateOnHeldOut(const FittedModel& model, const FitData& validation, int skip_step) {
  HeldOutCheck check;
  if (validation.channels.empty()) return check;
  const std::vector<Eigen::MatrixXcd> predicted = model.Phasors(validation);
  double chi2 = 0.0, error2 = 0.0, norm2 = 0.0;
  int steps = 0;
  for (std::size_t i = 0; i < validation.steps.size(); ++i) {
    if (static_cast<int>(i) == skip_step) continue;
    ++steps;
    const FitStep& s = validation.steps[i];
    for (int c = 0; c < static_cast<int>(validation.channels.size()); ++c) {
      for (int k = 1; k <= validation.num_fit_harmonics; ++k) {
        const Complex e = predicted[i](c, k - 1) - s.measured(c, k - 1);
        chi2 += Whitened(s, c, k, e).squaredNorm();
      }
      error2 += std::norm(predicted[i](c, 0) - s.measured(c, 0));
      norm2 += std::norm(s.measured(c, 0));
    }
  }
  check.chi_square = chi2;
  check.h1_relative_error = std::sqrt(error2 / std::max(norm2, 1e-300));
  check.num_residuals = 2 * steps * static_cast<int>(validation.channels.size()) * validation.num_fit_harmonics;
  return check;
}

// Iterations of the first start of a refit on the levels not left out.
constexpr int kLeftOutRefitMinIterations = 400;

HeldOutCheck ValidateOnLeftOutLevels(const FittedModel& model, const DiagnosisOptions& options) {
  const FitData& data = model.data;
  HeldOutCheck check;
  if (data.levels.size() < 2) return check;
  IdentifyOptions refit = CandidateRefitOptions(options, model.model_harmonics);
  // The model refitted to its own data less one level starts at its
  // optimum but, when it misses the data (the base model of a diagnosis),
  // far from the optimum of the rest: it is owed the first start's budget
  // of an identification, not a candidate's.
  refit.first_start_min_iterations = kLeftOutRefitMinIterations;
  double chi2 = 0.0, error2 = 0.0, norm2 = 0.0;
  int num_residuals = 0;
  for (const std::string& level : data.levels) {
    FitData seen = data, left_out = data;
    seen.steps.clear();
    left_out.steps.clear();
    for (const FitStep& s : data.steps) (s.level == level ? left_out : seen).steps.push_back(s);
    if (seen.steps.empty() || left_out.steps.empty()) continue;
    std::vector<double> values;
    try {
      const IdentifyResult r = IdentifyWith(
          [&] { return refit.family->MakeProblem(seen, model.structure, refit.model); }, model.structure,
          model.structure.Values(), refit);
      for (const auto& p : r.parameters) values.push_back(p.value);
    } catch (const std::exception&) {
      return {};
    }
    ModelStructure at = model.structure;
    at.SetValues(values);
    const std::unique_ptr<FitProblem> problem = refit.family->MakeProblem(left_out, at, refit.model);
    const Eigen::VectorXd x = problem->FeasiblePoint(values);
    chi2 += problem->WeightedResiduals(x).squaredNorm();
    num_residuals += left_out.NumResiduals();
    const std::vector<Eigen::MatrixXcd> predicted = ModelPhasors(left_out, *problem, x);
    for (std::size_t i = 0; i < left_out.steps.size(); ++i)
      for (int c = 0; c < static_cast<int>(left_out.channels.size()); ++c) {
        error2 += std::norm(predicted[i](c, 0) - left_out.steps[i].measured(c, 0));
        norm2 += std::norm(left_out.steps[i].measured(c, 0));
      }
  }
  if (num_residuals == 0) return check;
  check.chi_square = chi2;
  check.h1_relative_error = std::sqrt(error2 / std::max(norm2, 1e-300));
  check.num_residuals = num_residuals;
  return check;
}

LocationStage Locate(const FitData& fit, const BaseFit& base, const FitData& located_in) {
  LocationStage stage;
  const FitData& located = located_in.channels.empty() ? fit : located_in;
  try {
    const ModelStructure& fitted = base.model.structure;
    hb::LinearBeamModel reference = fitted.ApplyLinear({.beam = fit.beam, .attachments = fit.sensor_masses});
    reference.support_stiffness_Nm_rad = fitted.law->InitialStiffness_Nm_rad();
    reference.support_damping_Nms_rad = fitted.law->InitialDamping_Nms_rad();
    MisfitLocationOptions options{.num_fitted_parameters = static_cast<int>(base.summary.parameters.size())};
    // Propagated σ already hold every error stated beforehand. No allowance
    // is added, and the fit's estimated residual error is not either: it is
    // the misfit this test is for, and allowing it makes every base fit
    // pass (its estimate brings χ² to its dof by construction).
    if (located.uncertainty == PhasorUncertainty::kPropagated) options.model_relative_error = 0.0;
    stage.location = LocateMisfit(located, base.model.Phasors(located), fit.num_fit_harmonics, reference, options);
  } catch (const std::exception& e) {
    stage.error = e.what();
  }
  return stage;
}

namespace {

// A significant candidate that brings a base misfit beyond the noise within
// it, better than `best_chi_square`: nothing costlier needs to be tried. A
// base within the noise already says nothing of which candidate explains a
// significant gain, so none does there.
bool ExplainsBetter(const CandidateOutcome& o, const FitSummary& base, double best_chi_square,
                    const DiagnosisOptions& options) {
  return o.significant && base.reduced_chi_square > options.acceptable_reduced_chi_square &&
         o.fit.reduced_chi_square <= options.acceptable_reduced_chi_square && o.fit.chi_square < best_chi_square;
}

// One step's phasors set free (2·C·K parameters) absorb physics whose
// misfit gathers at one step too: a gram at the drive point moves the
// resonance, and the step at the high level's peak, just before the jump,
// carries most of the misfit (a 4 g mass was named that step's fault in 20
// of 20 realisations while it spared the physics). So it does not spare the
// physics refits: they compete, and the ranking (BIC, then the held-out
// prediction) chooses; a real outlier, which no physics fits, still wins.
bool SparesThePhysics(const CandidateOutcome& o) {
  return !o.name.starts_with(std::string(ArtefactKindName(ArtefactKind::kOutlyingStep)) + "(");
}

}  // namespace

CandidateRefits RefitCandidates(const FitData& fit, const BaseFit& base, const std::optional<MisfitLocation>& location,
                                const DiagnosisOptions& options, const RefitProgress& progress,
                                const std::string& explained_by_recording, int num_candidates) {
  RefitRun run = PlanRefits(fit, base, options);
  // The linear candidates first (cheap: the base's law and harmonics). When
  // one of them is significant and brings the misfit within the noise, no
  // costlier refit could explain more than noise: those are not run (a
  // diagnosis of 99 steps took 40 s with them, 15 s without).
  const std::pair<int, int> base_cost{options.model_harmonics, 0};
  std::vector<int> cheap, costly;
  for (int j = 0; j < static_cast<int>(run.jobs.size()); ++j)
    (Cost(run.extensions[run.jobs[j].candidate]) > base_cost ? costly : cheap).push_back(j);
  // The recording first: when a fault of it explains the misfit, no physics is refitted.
  if (!explained_by_recording.empty()) cheap.clear();
  RunRefits(fit, options, progress, &run, cheap);
  CandidateRefits refits;
  refits.models.resize(run.library.size());
  refits.outcomes.resize(run.library.size());
  // The linear candidate that explains the misfit best (ExplainsBetter), or
  // the base itself when it fits within the noise and no linear candidate is
  // significant: then the costly candidates are not refitted.
  const bool base_within_noise = base.summary.reduced_chi_square <= options.acceptable_reduced_chi_square;
  std::string explained_by = explained_by_recording;
  bool any_significant = false;
  double explained_chi_square = base.summary.chi_square;
  auto test = [&](int c) {
    CandidateOutcome outcome = DescribeCandidate(run, c, location);
    if (run.best_job[c] >= 0)
      refits.models[c] = TestCandidate(fit, base.summary, run, c, options, num_candidates, &outcome);
    refits.outcomes[c] = std::move(outcome);
  };
  std::vector<bool> tested(run.library.size(), false);
  for (int j : cheap) {
    const int c = run.jobs[j].candidate;
    if (tested[c]) continue;
    tested[c] = true;
    test(c);
    const CandidateOutcome& o = refits.outcomes[c];
    any_significant |= o.significant;
    if (ExplainsBetter(o, base.summary, explained_chi_square, options)) {
      explained_by = o.name;
      explained_chi_square = o.fit.chi_square;
    }
  }
  if (explained_by.empty() && base_within_noise && !any_significant) explained_by = "the base model";
  if (explained_by.empty() && !costly.empty())
    RunRefits(fit, options, progress, &run, costly, static_cast<int>(cheap.size()));
  for (int c = 0; c < static_cast<int>(run.library.size()); ++c) {
    if (tested[c]) continue;
    if (explained_by.empty()) {
      test(c);
    } else {
      refits.outcomes[c] = DescribeCandidate(run, c, location);
      refits.outcomes[c].status = RefitStatus::kNotRefitted;
      refits.outcomes[c].status_message = explained_by + " already fits within the noise";
    }
  }
  return refits;
}

bool SeparatedInSample(const FitSummary& a, const FitSummary& b) {
  const FitSummary& better = a.chi_square <= b.chi_square ? a : b;
  const double scale = std::max(1.0, better.reduced_chi_square);
  return std::abs(a.chi_square - b.chi_square) / scale > kDecisiveChiSquare;
}

bool SeparatedHeldOut(const FitSummary& a, const FitSummary& b) {
  if (!std::isfinite(a.held_out_chi_square) || !std::isfinite(b.held_out_chi_square)) return false;
  const FitSummary& better = a.held_out_chi_square <= b.held_out_chi_square ? a : b;
  const double scale =
      std::max(1.0, better.held_out_num_residuals > 0 ? better.held_out_chi_square / better.held_out_num_residuals : 1.0);
  return std::abs(a.held_out_chi_square - b.held_out_chi_square) / scale > kDecisiveChiSquare;
}

CandidateRefits RefitPairs(const FitData& fit, const FittedModel& first, const CandidateOutcome& first_outcome,
                           const std::vector<std::string>& partners, const DiagnosisOptions& options,
                           const RefitProgress& progress) {
  RefitRun run = PlanPairs(fit, first, first_outcome, partners, options);
  CandidateRefits pairs;
  if (run.jobs.empty()) return pairs;
  RunRefits(fit, options, progress, &run, AllJobs(run));
  pairs.models.resize(run.library.size());
  for (int c = 0; c < static_cast<int>(run.library.size()); ++c) {
    CandidateOutcome outcome = DescribeCandidate(run, c, std::nullopt);
    if (run.best_job[c] >= 0) pairs.models[c] = TestCandidate(fit, first_outcome.fit, run, c, options, 0, &outcome);
    pairs.outcomes.push_back(std::move(outcome));
  }
  return pairs;
}

std::vector<std::string> PairPartners(const std::vector<CandidateOutcome>& ranked, const std::string& cause,
                                      const DiagnosisOptions& options) {
  // Every other candidate with parameters of its own: a second effect can
  // barely show from the base while the first dominates the misfit (a
  // compliant clamp beside friction removed 4 % of the base χ² alone, or its
  // refit failed there). Converged ones first, best BIC first; then failed
  // ones by signature score.
  std::vector<const CandidateOutcome*> order;
  for (const CandidateOutcome& c : ranked)
    if (c.name != cause && c.Refitted() && !c.extra_parameters.empty()) order.push_back(&c);
  std::vector<const CandidateOutcome*> failed;
  for (const CandidateOutcome& c : ranked)
    if (c.name != cause && !c.Refitted() && !c.extra_parameters.empty()) failed.push_back(&c);
  std::stable_sort(failed.begin(), failed.end(), [](const CandidateOutcome* a, const CandidateOutcome* b) {
    return a->signature_score > b->signature_score;
  });
  order.insert(order.end(), failed.begin(), failed.end());
  std::vector<std::string> partners;
  for (const CandidateOutcome* c : order)
    if (static_cast<int>(partners.size()) < options.max_pair_partners) partners.push_back(c->name);
  return partners;
}

int ChoosePair(const std::vector<CandidateOutcome>& pairs, const FitSummary& first) {
  int chosen = -1;
  for (int p = 0; p < static_cast<int>(pairs.size()); ++p) {
    const CandidateOutcome& pair = pairs[p];
    // Validates: predicts the held-out channels at least as well as the
    // first cause alone (when there are any).
    const bool validates = !std::isfinite(first.held_out_chi_square) ||
                           (std::isfinite(pair.fit.held_out_chi_square) &&
                            pair.fit.held_out_chi_square <= first.held_out_chi_square);
    if (!pair.significant || !validates) continue;
    if (chosen < 0 || pair.fit.bic < pairs[chosen].fit.bic) chosen = p;
  }
  return chosen;
}

Verdict DecideVerdict(const FitSummary& base, const std::optional<MisfitLocation>& location,
                      PhasorUncertainty weighting, const std::vector<CandidateOutcome>& candidates,
                      const DiagnosisOptions& options, RankedBy validated_on) {
  Verdict v;
  v.ranking.resize(candidates.size());
  for (int c = 0; c < static_cast<int>(v.ranking.size()); ++c) v.ranking[c] = c;
  std::stable_sort(v.ranking.begin(), v.ranking.end(), [&](int a, int b) {
    const CandidateOutcome &x = candidates[a], &y = candidates[b];
    if (x.significant != y.significant) return x.significant;
    if (x.Refitted() != y.Refitted()) return x.Refitted();
    if (x.Refitted() && x.fit.bic != y.fit.bic) return x.fit.bic < y.fit.bic;
    return x.signature_score > y.signature_score;
  });
  int num_significant = 0;
  while (num_significant < static_cast<int>(v.ranking.size()) && candidates[v.ranking[num_significant]].significant)
    ++num_significant;
  const bool held_out = num_significant > 0 && std::isfinite(candidates[v.ranking.front()].fit.held_out_chi_square);
  // Validation: the significant candidate that predicts the held-out
  // channels best goes first when it does so decisively.
  if (held_out) {
    int best = 0;
    for (int r = 1; r < num_significant; ++r) {
      const FitSummary& f = candidates[v.ranking[r]].fit;
      if (std::isfinite(f.held_out_chi_square) && f.held_out_chi_square < candidates[v.ranking[best]].fit.held_out_chi_square)
        best = r;
    }
    if (best > 0 && SeparatedHeldOut(candidates[v.ranking[best]].fit, candidates[v.ranking.front()].fit))
      std::rotate(v.ranking.begin(), v.ranking.begin() + best, v.ranking.begin() + best + 1);
  }
  if (num_significant > 0) {
    v.cause = v.ranking.front();
    v.verdict = DiagnosisVerdict::kCauseNamed;
    v.ranked_by = held_out ? validated_on : RankedBy::kInSampleBic;
    v.selected = {candidates[v.cause].name};
    if (num_significant > 1) {
      const FitSummary &a = candidates[v.cause].fit, &b = candidates[v.ranking[1]].fit;
      if (!SeparatedInSample(a, b) && !SeparatedHeldOut(a, b)) {
        v.tied_with = v.ranking[1];
        v.verdict = DiagnosisVerdict::kCausesIndistinguishable;
        v.selected.push_back(candidates[v.tied_with].name);
      }
    }
  } else {
    // Under propagated σ the location's test states its own false-alarm
    // rate, and a misfit it finds is reported whatever the reduced χ²; the
    // relative floor's σ are not a noise model, so there a misfit must also
    // exceed the acceptable reduced χ².
    const bool misfit = location && weighting == PhasorUncertainty::kPropagated
                            ? location->significant
                            : base.reduced_chi_square > options.acceptable_reduced_chi_square &&
                                  (!location || location->significant);
    v.verdict = misfit ? DiagnosisVerdict::kUnexplained : DiagnosisVerdict::kNoSignificantDiscrepancy;
    v.selected = {"none"};
  }
  return v;
}

DiagnosisResult Diagnose(const FitData& fit, const FitData& validation, const FitData& located,
                         const DiagnosisOptions& options, const DiagnosisProgress& progress) {
  options.Validate();
  const auto started = std::chrono::steady_clock::now();
  auto report = [&](double fraction, const std::string& what) {
    if (progress) progress(fraction, what);
  };
  DiagnosisResult result;
  report(0.0, "base fit");
  const BaseFit base = FitBase(fit, options);
  result.base = base.summary;
  ApplyHeldOut(ValidateOnHeldOut(base.model, validation), &result.base);

  report(0.15, "locating the misfit");
  LocationStage location = Locate(fit, base, located);
  result.location = std::move(location.location);
  result.location_error = std::move(location.error);

  for (const FitStep& s : fit.steps)
    if (s.unsettled)
      result.recording_findings.push_back(fmt::format(
          "step {} {:.4g} Hz ({}) was recorded before it settled (its analysed part changes by {:.2f} % between "
          "halves); its uncertainty includes that change",
          s.level, s.FrequencyHz(), s.file, 100.0 * s.unsettled_change_relative));

  // The recording first (an engineer whose fit fails checks the recording
  // before the model): its artefacts are cheap refits of the base physics.
  const int num_physics = static_cast<int>(SelectedCandidates(options).size());
  CandidateRefits artefacts;
  if (options.measurement_artefacts) {
    report(0.2, "checking the recording");
    artefacts = RefitMeasurementArtefacts(fit, validation, base, options, num_physics,
                                          [&](int done, int num, const std::string& name) {
                                            report(0.2 + 0.2 * done / static_cast<double>(num),
                                                   "recording check " + std::to_string(done) + "/" +
                                                       std::to_string(num) + " (" + name + ")");
                                          });
  }
  std::string explained_by;
  double explained_chi_square = base.summary.chi_square;
  for (const CandidateOutcome& o : artefacts.outcomes)
    if (SparesThePhysics(o) && ExplainsBetter(o, base.summary, explained_chi_square, options)) {
      explained_by = o.name;
      explained_chi_square = o.fit.chi_square;
    }
  CandidateRefits refits = RefitCandidates(
      fit, base, result.location, options,
      [&](int done, int num_jobs, const std::string& name) {
        report(0.4 + 0.5 * done / static_cast<double>(num_jobs),
               "refit " + std::to_string(done) + "/" + std::to_string(num_jobs) + " (" + name + ")");
      },
      explained_by, num_physics + static_cast<int>(artefacts.outcomes.size()));
  refits.outcomes.insert(refits.outcomes.begin(), std::make_move_iterator(artefacts.outcomes.begin()),
                         std::make_move_iterator(artefacts.outcomes.end()));
  refits.models.insert(refits.models.begin(), std::make_move_iterator(artefacts.models.begin()),
                       std::make_move_iterator(artefacts.models.end()));
  for (std::size_t c = 0; c < refits.models.size(); ++c)  // (the recording's checked their own)
    if (refits.models[c] && !refits.outcomes[c].measurement)
      ApplyHeldOut(ValidateOnHeldOut(*refits.models[c], validation), &refits.outcomes[c].fit);

  // Without a held-out channel, the levels left out in turn validate the
  // base and the best significant candidates (each costs a refit per level).
  const bool by_levels = validation.channels.empty() && fit.levels.size() >= 2;
  if (by_levels) {
    report(0.8, "validating on the levels left out in turn");
    ApplyHeldOut(ValidateOnLeftOutLevels(base.model, options), &result.base);
    for (int c : BestSignificant(refits.outcomes, kLevelValidatedCandidates))
      if (refits.models[c]) ApplyHeldOut(ValidateOnLeftOutLevels(*refits.models[c], options), &refits.outcomes[c].fit);
  }
  const RankedBy validated_on = by_levels ? RankedBy::kLevelsLeftOut : RankedBy::kHeldOutChannels;
  const Verdict verdict = DecideVerdict(result.base, result.location, fit.uncertainty, refits.outcomes, options, validated_on);
  for (int c : verdict.ranking) result.candidates.push_back(refits.outcomes[c]);
  result.verdict = verdict.verdict;
  result.ranked_by = verdict.ranked_by;
  result.selected = verdict.selected;
  const bool named = verdict.cause >= 0;
  if (named) result.blame = refits.outcomes[verdict.cause].measurement ? Blame::kRecording : Blame::kModel;
  result.final_fit = named ? refits.outcomes[verdict.cause].fit : result.base;
  result.rest_within_noise = result.final_fit.reduced_chi_square <= options.acceptable_reduced_chi_square;
  if (named) result.final_extra_parameters = refits.outcomes[verdict.cause].extra_parameters;

  // A cause that leaves a misfit beyond the noise: a second cause beside it.
  const FittedModel* final_model = named ? refits.models[verdict.cause].get() : &base.model;
  CandidateRefits pairs;
  // (Not after a fault of the recording: its refit fitted corrected data, which the pairs' refits would not.)
  if (named && verdict.tied_with < 0 && !result.rest_within_noise && refits.models[verdict.cause] &&
      !refits.outcomes[verdict.cause].measurement) {
    const std::vector<std::string> partners =
        PairPartners(result.candidates, refits.outcomes[verdict.cause].name, options);
    report(0.85, "pairs with " + refits.outcomes[verdict.cause].name);
    pairs = RefitPairs(fit, *refits.models[verdict.cause], refits.outcomes[verdict.cause], partners, options);
    for (std::size_t c = 0; c < pairs.models.size(); ++c)
      if (pairs.models[c]) ApplyHeldOut(ValidateOnHeldOut(*pairs.models[c], validation), &pairs.outcomes[c].fit);
    if (by_levels) {
      for (int c : BestSignificant(pairs.outcomes, kLevelValidatedCandidates))
        if (pairs.models[c]) ApplyHeldOut(ValidateOnLeftOutLevels(*pairs.models[c], options), &pairs.outcomes[c].fit);
    }
    const int chosen = ChoosePair(pairs.outcomes, refits.outcomes[verdict.cause].fit);
    if (chosen >= 0) {
      const CandidateOutcome& pair = pairs.outcomes[chosen];
      result.verdict = DiagnosisVerdict::kCombinationNamed;
      result.selected = {refits.outcomes[verdict.cause].name,
                         pair.name.substr(refits.outcomes[verdict.cause].name.size() + 3)};
      result.final_fit = pair.fit;
      result.final_extra_parameters = pair.extra_parameters;
      result.rest_within_noise = result.final_fit.reduced_chi_square <= options.acceptable_reduced_chi_square;
      final_model = pairs.models[chosen].get();
    }
    result.combinations = pairs.outcomes;
  }
  if (verdict.tied_with >= 0 && refits.models[verdict.cause] && refits.models[verdict.tied_with]) {
    report(0.92, "where to measure next");
    result.suggestion = SuggestMeasurement(fit, *refits.models[verdict.cause], refits.outcomes[verdict.cause].name,
                                           *refits.models[verdict.tied_with], refits.outcomes[verdict.tied_with].name);
  }
  // A fault of the recording refits corrected data under the base physics,
  // whose model form is identify's question, not the cause's.
  if (options.damping_laws && result.blame == Blame::kModel && final_model != nullptr) {
    report(0.93, "refitting the selected model under the other beam damping laws");
    result.final_damping_laws =
        FitDampingLaws(final_model->data, final_model->structure, result.final_fit.parameters,
                       result.final_fit.chi_square, result.final_fit.degrees_of_freedom,
                       CandidateRefitOptions(options, final_model->model_harmonics));
  }
  report(0.95, "response curves");
  double final_clock_error = 0.0;
  if (named && final_model == refits.models[verdict.cause].get() &&
      refits.outcomes[verdict.cause].name == ArtefactKindName(ArtefactKind::kClockError))
    for (const ParameterEstimate& p : refits.outcomes[verdict.cause].fit.parameters)
      if (p.name == ArtefactKindName(ArtefactKind::kClockError)) final_clock_error = p.value;
  result.response = ResponseCurves(fit, validation, base.model, *final_model, final_clock_error);
  // A fault of the recording leaves the physics, and so the backbone, the base's.
  if (result.blame == Blame::kModel && final_model != &base.model) {
    report(0.97, "the selected model's backbone");
    result.final_backbone = FinalBackbone(*final_model, options.backbone_points);
  }
  result.summary = WriteSummary(result);
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  report(1.0, "done");
  return result;
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
