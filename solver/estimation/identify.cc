#include "solver/estimation/identify.h"

#include "hb/errors.h"
#include "hb/option_checks.h"

#include "solver/estimation/gauss_newton_polish.h"
#include "solver/estimation/internal/ipopt_program.h"
#include "solver/estimation/internal/worker_processes.h"
#include "solver/estimation/parameter_covariance.h"
#include "solver/estimation/start_record_io.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <optional>
#include <random>
#include <thread>

#include <Eigen/Cholesky>
#include <fmt/format.h>

namespace beamid::solver {
namespace {

// Latin hypercube in [0, 1)^dimensions.
std::vector<std::vector<double>> LatinHypercube(int count, int dimensions, unsigned seed) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  std::vector<std::vector<double>> points(count, std::vector<double>(dimensions));
  for (int d = 0; d < dimensions; ++d) {
    std::vector<int> order(count);
    for (int i = 0; i < count; ++i) order[i] = i;
    std::shuffle(order.begin(), order.end(), random);
    for (int i = 0; i < count; ++i) points[i][d] = (order[i] + uniform(random)) / count;
  }
  return points;
}

// Re-seeding an end point's states on the measured branch must lower the
// misfit by more than this (relative) to be worth another run.
constexpr double kRepairGain = 1e-6;
constexpr int kMaxBranchRepairs = 3;
// A start that ran out of iterations may go on for this many more.

// One Ipopt run from x0, which `problem` has just scaled at `scaled_at`.
StartOutcome RunFrom(FitProblem& problem, const IpoptOptions& ipopt, const Eigen::VectorXd& x0,
                     const std::vector<double>& scaled_at, Eigen::VectorXd* x_out) {
  const internal::IpoptOutcome outcome = internal::RunIpopt(problem, x0, ipopt);
  *x_out = outcome.x;
  return {.parameters = problem.Parameters(outcome.x),
          .objective = problem.Objective(outcome.x),
          .success = outcome.success,
          .iterations = outcome.iterations,
          .status = outcome.status_text,
          .status_code = outcome.status,
          .scaled_at = scaled_at};
}

// Where a start's states begin. Solved by harmonic balance at the start's
// own parameters, they describe the data only as well as those parameters
// do: far from the optimum they lie off the data, often on the other branch
// of a fold, and Ipopt then wandered (measured: from a factor 3 away 1 of 9
// starts converged, and to a local minimum with one step of the top level
// on the wrong branch). Seeded instead at the rotation the sensors show (the
// measured branch), the constraints are nearly linear in a polynomial law's
// parameters and such a start converges in < 10 iterations. With other laws
// (friction, one-sided stiffness) the seeded start may converge slowly or
// not at all where the feasible one converges in ~20 iterations, so the
// seeded start is a probe of kSeededProbeIterations; a start it does not
// settle goes on from feasible states with the full budget, and, should that
// fail too, seeded with the full budget.
constexpr int kSeededProbeIterations = 25;

StartOutcome RunStart(FitProblem& problem, const IdentifyOptions& options, const std::vector<double>& start,
                      bool first, Eigen::VectorXd* x_out) {
  IpoptOptions ipopt = options.ipopt;
  if (first) ipopt.max_iterations = std::max(ipopt.max_iterations, options.first_start_min_iterations);
  struct Attempt {
    StartRoute route;
    int max_iterations;
  };
  std::vector<Attempt> attempts = {{StartRoute::kFeasibleStates, ipopt.max_iterations}};
  if (options.seed_states_from_measurements) {
    attempts.insert(attempts.begin(),
                    {StartRoute::kMeasuredStates, std::min(kSeededProbeIterations, ipopt.max_iterations)});
    if (ipopt.max_iterations > kSeededProbeIterations)
      attempts.push_back({StartRoute::kMeasuredStates, ipopt.max_iterations});
  }
  // Each route's starting point is made once (both set the same scales).
  std::optional<Eigen::VectorXd> seeded, feasible;
  StartOutcome best;
  Eigen::VectorXd x;
  int iterations = 0;
  for (const Attempt& attempt : attempts) {
    std::optional<Eigen::VectorXd>& x0 = attempt.route == StartRoute::kMeasuredStates ? seeded : feasible;
    if (!x0)
      x0 = attempt.route == StartRoute::kMeasuredStates ? problem.MeasuredStatePoint(start) : problem.FeasiblePoint(start);
    IpoptOptions limited = ipopt;
    limited.max_iterations = attempt.max_iterations;
    Eigen::VectorXd x_attempt;
    StartOutcome outcome = RunFrom(problem, limited, *x0, start, &x_attempt);
    outcome.route = attempt.route;
    const bool better = iterations == 0 || (outcome.success && !best.success) ||
                        (outcome.success == best.success && outcome.objective < best.objective);
    iterations += outcome.iterations;
    if (better) {
      best = outcome;
      x = x_attempt;
    }
    if (best.success) break;
  }
  best.start = start;
  best.iterations = iterations;
  *x_out = x;
  return best;
}

// The best end point's states re-seeded on the measured branch at its own
// parameters: if that lowers the misfit, a step had converged on the other
// branch of a fold (a local minimum whose intervals would not hold the
// answer), and the fit is re-run from there, up to kMaxBranchRepairs times.
// Done for the winner only: the other starts do not change the result.
void RepairBranches(FitProblem& problem, const IdentifyOptions& options, StartOutcome* best, Eigen::VectorXd* x) {
  IpoptOptions ipopt = options.ipopt;
  ipopt.max_iterations = std::max(ipopt.max_iterations, options.first_start_min_iterations);
  for (int repair = 0; best->success && repair < kMaxBranchRepairs; ++repair) {
    const std::vector<double> at = best->parameters;
    const Eigen::VectorXd reseeded = problem.FeasiblePoint(at);
    if (!(problem.Objective(reseeded) < best->objective * (1.0 - kRepairGain))) return;
    Eigen::VectorXd x_repaired;
    StartOutcome repaired = RunFrom(problem, ipopt, reseeded, at, &x_repaired);
    if (!repaired.success || !(repaired.objective < best->objective)) return;
    repaired.start = best->start;
    repaired.route = best->route;
    repaired.iterations += best->iterations;
    repaired.branch_repairs = best->branch_repairs + 1;
    *best = repaired;
    *x = x_repaired;
  }
}

// Physical bounds on k2 and k3 from the data: over the rotations the test
// reached, the nonlinear terms cannot change the support's stiffness by more
// than kMaxStiffnessChange times the beam's own rotational stiffness EI/L (a
// support that much stiffer acts as a clamp; the data could not tell more).
// Without them a start far from the optimum can run off to |k3| ~ 1e11.
ModelStructure WithDataBounds(const ModelStructure& structure, const hb::BeamProperties& beam, double max_rotation_rad) {
  constexpr double kMaxStiffnessChange = 100.0;
  ModelStructure bounded = structure;
  if (!dynamic_cast<const hb::PolynomialSupportLaw*>(structure.law.get()) || !(max_rotation_rad > 0.0)) return bounded;
  const double beam_stiffness_Nm_rad = beam.BendingStiffness_Nm2() / beam.length_m;
  const double k2_limit = kMaxStiffnessChange * beam_stiffness_Nm_rad / max_rotation_rad;
  const double k3_limit = k2_limit / max_rotation_rad;
  const std::vector<double> values = structure.Values();
  for (auto [j, limit] : {std::pair{1, k2_limit}, std::pair{2, k3_limit}}) {
    ParameterBounds& b = bounded.law_bounds[j];
    // Never exclude the caller's own start.
    const double reach = std::max(limit, 2.0 * std::abs(values[j]));
    b.lower = std::max(b.lower, -reach);
    b.upper = std::min(b.upper, reach);
  }
  return bounded;
}

// Starts from the direct estimate of the polynomial law with any model; the
// model is built on the structure with the data's bounds.
using BoundedProblemFactory = std::function<std::unique_ptr<FitProblem>(const ModelStructure&)>;

// The linear fit's continuation (IdentifyOptions::linear_continuation): the
// nonlinear coefficients' share of their data bounds at each stage. The
// linear model (share 0) has one optimum and converges from the direct
// estimate; each wider stage starts where the narrower one ended, so the fit
// follows its optimum out of the linear regime instead of jumping into it.
constexpr double kLinearContinuationShares[] = {0.0, 1e-2, 1e-1, 1.0};

// The linear stage starts from the direct estimate's k1 and c (a linear
// least-squares fit of the same data), its states seeded at the measured
// rotation whatever the caller chose: this is the rescue, not the comparison.
IdentifyResult ContinueFromLinearFit(const BoundedProblemFactory& make_problem, const ModelStructure& bounded,
                                     std::vector<double> from, const DirectEstimate& direct,
                                     const IdentifyOptions& options, const ProgressCallback& progress,
                                     const std::string& tried) {
  IdentifyOptions stage_options = options;
  stage_options.num_starts = 0;
  stage_options.linear_continuation = false;
  stage_options.seed_states_from_measurements = true;
  const auto bounds = bounded.Bounds();
  if (std::isfinite(direct.k1_Nm_rad) && std::isfinite(direct.c_Nms_rad)) {
    from[0] = std::clamp(direct.k1_Nm_rad, bounds[0].lower, bounds[0].upper);
    from[3] = std::clamp(direct.c_Nms_rad, bounds[3].lower, bounds[3].upper);
    from[3] = std::max(from[3], 1e-3 * bounds[3].typical);
  }
  const std::vector<ParameterBounds> full = bounded.law_bounds;
  IdentifyResult result;
  std::string path;
  for (double share : kLinearContinuationShares) {
    ModelStructure stage = bounded;
    for (int j : {1, 2}) {
      stage.law_bounds[j].lower = share * full[j].lower;
      stage.law_bounds[j].upper = share * full[j].upper;
      from[j] = std::clamp(from[j], stage.law_bounds[j].lower, stage.law_bounds[j].upper);
    }
    if (progress) progress(0.0, share == 0.0 ? "linear fit" : "continuation from the linear fit");
    try {
      result = IdentifyWith([&] { return make_problem(stage); }, stage, from, stage_options);
    } catch (const NumericalError& e) {
      throw NumericalError(tried + "; continuation from the linear fit (k2 = k3 = 0" + path + ") then ended with: " +
                           e.what());
    }
    for (std::size_t k = 0; k < from.size(); ++k) from[k] = result.parameters[k].value;
    if (share > 0.0) path += ", " + std::to_string(share) + " of their range";
  }
  result.warnings.insert(result.warnings.begin(),
                         tried + "; the fit was found by continuation in the parameters from the linear fit (k2 = k3 "
                                 "= 0, then their range opened to 1 %, 10 % and all of it, each stage from the last)");
  return result;
}
IdentifyResult IdentifyFromDirectEstimate(const BoundedProblemFactory& make_problem, const FitData& data,
                                          const ModelStructure& structure, const IdentifyOptions& options,
                                          const ProgressCallback& progress) {
  // 1. Direct estimate from the reconstructed support (polynomial part).
  if (progress) progress(0.0, "direct estimate");
  hb::LinearBeamModel nominal{.beam = data.beam, .attachments = data.sensor_masses};
  nominal.beam.loss_factor = options.model.beam_loss_factor;
  const DirectEstimate direct = EstimatePolynomialDirectly(ReconstructSupport(data, structure.ApplyLinear(nominal)));
  const ModelStructure bounded = WithDataBounds(structure, nominal.beam, direct.max_rotation_rad);
  std::vector<double> first = structure.Values();
  if (options.use_direct_estimate && dynamic_cast<const hb::PolynomialSupportLaw*>(structure.law.get())) {
    first[0] = direct.k1_Nm_rad;
    first[1] = direct.k2_Nm_rad2;
    first[2] = direct.k3_Nm_rad3;
    first[3] = direct.c_Nms_rad;
    const auto bounds = bounded.Bounds();
    for (int j = 0; j < 4; ++j) first[j] = std::clamp(first[j], bounds[j].lower, bounds[j].upper);
    // A zero damping start sits on its bound, where the interior method
    // cannot start: nudge it inside.
    first[3] = std::max(first[3], 1e-3 * bounds[3].typical);
  }
  const auto started = std::chrono::steady_clock::now();
  IdentifyResult result;
  try {
    result = IdentifyWith([&] { return make_problem(bounded); }, bounded, first, options, progress);
  } catch (const NumericalError& e) {
    if (!options.linear_continuation || !dynamic_cast<const hb::PolynomialSupportLaw*>(structure.law.get())) throw;
    result = ContinueFromLinearFit(make_problem, bounded, first, direct, options, progress, e.what());
    result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  }
  result.direct = direct;
  return result;
}

// The continuation from the best end point runs in chunks of this many
// iterations, and ends as stalled once a chunk changes χ² by less than
// kStalledRelativeChange of itself (measured on a one-level misfit: it
// wobbles by 3e-6 of itself from chunk to chunk, a change of χ² below 1) at a point whose balance holds (its
// constraint violation within kStalledConstraintFactor × the tolerance).
constexpr int kContinuationChunkIterations = 200;
constexpr double kStalledRelativeChange = 1e-5;
constexpr double kStalledConstraintFactor = 10.0;

double MaxConstraintViolation(FitProblem& problem, const Eigen::VectorXd& x) {
  Eigen::VectorXd c;
  problem.Constraints(x, &c);
  return c.size() == 0 ? 0.0 : c.cwiseAbs().maxCoeff();
}

// When no start converged: the start whose end point has the least misfit
// goes on from there for options.continuation_iterations more. A model that misses
// the data (physics it lacks) slows Ipopt down near the optimum rather than
// leaving it without one; the user is owed that fit and its verdict, not
// "no start converged". Returns the index of the continued start, or throws
// NumericalError with what was tried.
int ContinueFromBestEndPoint(const ProblemFactory& make_problem, const IdentifyOptions& options,
                             IdentifyResult& result, std::vector<Eigen::VectorXd>& finals) {
  int nearest = -1;
  for (int i = 0; i < static_cast<int>(result.starts.size()); ++i)
    if (finals[i].size() > 0 && std::isfinite(result.starts[i].objective) && !result.starts[i].scaled_at.empty() &&
        (nearest < 0 || result.starts[i].objective < result.starts[nearest].objective))
      nearest = i;
  std::string tried = "no start converged (first start: " + result.starts[0].status + ")";
  if (options.continuation_iterations == 0 && !options.polish_end_point) throw NumericalError(tried);
  if (nearest < 0) throw NumericalError(tried + "; no start reached a point to continue from");
  const std::unique_ptr<FitProblem> problem = make_problem();
  StartOutcome& outcome = result.starts[nearest];
  if (options.polish_end_point) {
    if (const std::optional<PolishedPoint> polished = PolishInReducedSpace(*problem, outcome.parameters)) {
      outcome.parameters = polished->parameters;
      outcome.objective = 0.5 * polished->chi_square;
      outcome.scaled_at = polished->parameters;
      finals[nearest] = polished->x;
      outcome.success = true;
      outcome.status = fmt::format(
          "stationary after Gauss–Newton steps from the best end point (chi-square could fall by {:.2g} more)",
          polished->decrement);
      result.warnings.push_back(tried + "; " + outcome.status);
      return nearest;
    }
    if (options.continuation_iterations == 0)
      throw NumericalError(tried + "; Gauss–Newton steps from the best end point did not reach a stationary point");
  }
  problem->FeasiblePoint(outcome.scaled_at);
  // In chunks, so that a fit that has stopped improving ends there: on a
  // model that misses the data, parameters the data cannot tell apart (the
  // beam's η and the support's c on one level) leave a valley along which
  // Ipopt's tolerance is never met while χ² no longer changes (measured:
  // 3000 iterations for a change in χ² of 1e-4). Its end point is the fit
  // the user is owed, with the verdict that it misses the data, and the
  // covariance shows how little the valley's direction is determined.
  IpoptOptions ipopt = options.ipopt;
  ipopt.max_iterations = std::min(kContinuationChunkIterations, options.continuation_iterations);
  Eigen::VectorXd x = finals[nearest];
  StartOutcome continued;
  continued.objective = outcome.objective;
  bool stalled = false;
  int iterations = 0;
  while (iterations < options.continuation_iterations) {
    Eigen::VectorXd x_next;
    const double before = continued.objective;
    StartOutcome chunk = RunFrom(*problem, ipopt, x, outcome.scaled_at, &x_next);
    iterations += chunk.iterations;
    // The barrier may trade a little misfit for feasibility: a chunk that
    // ends higher still moved, and the next goes on from it.
    const double change = std::abs(chunk.objective - before);
    continued = chunk;
    x = x_next;
    if (continued.success) break;
    stalled = change <= kStalledRelativeChange * before &&
              MaxConstraintViolation(*problem, x) <= kStalledConstraintFactor * options.ipopt.constraint_tolerance;
    if (stalled) break;
  }
  continued.iterations = iterations;
  if (!continued.success && !stalled)
    throw NumericalError(tried + "; continuing from the best end point (start " + std::to_string(nearest + 1) +
                         ", chi-square " + std::to_string(2.0 * outcome.objective) + ") for " +
                         std::to_string(iterations) + " more iterations ended with: " +
                         (continued.status.empty() ? "no lower misfit" : continued.status));
  if (stalled) {
    continued.success = true;
    continued.status = "stopped where the misfit no longer changes (chi-square changed by less than " +
                       fmt::format("{:g}", kStalledRelativeChange) + " of itself over " +
                       std::to_string(kContinuationChunkIterations) + " iterations)";
    result.warnings.push_back(tried + "; the fit went on from the best end point (start " +
                              std::to_string(nearest + 1) + ") and " + continued.status +
                              ": Ipopt's tolerance was not met, so parameters the data do not tell apart may lie "
                              "anywhere along a valley of equal misfit (see their correlation and intervals)");
  } else {
    result.warnings.push_back(tried + "; the fit went on from the best end point (start " +
                              std::to_string(nearest + 1) + ") and converged after " +
                              std::to_string(iterations) + " more iterations");
  }
  continued.start = outcome.start;
  continued.route = outcome.route;
  continued.iterations += outcome.iterations;
  outcome = continued;
  finals[nearest] = x;
  return nearest;
}

}  // namespace

void IdentifyOptions::Validate() const {
  using namespace option_checks;
  model.Validate();
  ipopt.Validate();
  // The command line's limits (--starts, --threads).
  RequireInRange("IdentifyOptions.num_starts", num_starts, 0, 1000);
  // [value/spread, value·spread] is empty or inverted at a spread of 1 or below.
  RequireAbove("IdentifyOptions.start_spread", start_spread, 1.0);
  if (family == nullptr) Refuse("IdentifyOptions.family", "null", "a model family (solver/estimation/model_family.h)");
  RequireInRange("IdentifyOptions.num_workers (worker processes, 0: one per core)", num_workers, 0, 256);
  RequireInRange("IdentifyOptions.continuation_iterations", continuation_iterations, 0, 100000);
  RequireInRange("IdentifyOptions.first_start_min_iterations", first_start_min_iterations, 0, 100000);
  RequirePositive("IdentifyOptions.decisive_chi_square_gap", decisive_chi_square_gap);
}

IdentifyResult Identify(const FitData& data, const ModelStructure& structure, const IdentifyOptions& options,
                        const ProgressCallback& progress) {
  options.Validate();
  options.family->CheckCanHold(data, structure, options.model);
  return IdentifyFromDirectEstimate(
      [&](const ModelStructure& bounded) { return options.family->MakeProblem(data, bounded, options.model); }, data,
      structure, options, progress);
}

IdentifyResult IdentifyWith(const ProblemFactory& make_problem, const ModelStructure& structure,
                            const std::vector<double>& first, const IdentifyOptions& options,
                            const ProgressCallback& progress) {
  options.Validate();
  const auto started = std::chrono::steady_clock::now();
  IdentifyResult result;
  const ModelStructure& initial = structure;

  // 2. Starts: the direct estimate, then a Latin hypercube around it.
  std::vector<std::vector<double>> starts = {first};
  const auto bounds = initial.Bounds();
  const int num_parameters = initial.NumParameters();
  for (const auto& u : LatinHypercube(options.num_starts, num_parameters, options.seed)) {
    std::vector<double> start = first;
    for (int j = 0; j < num_parameters; ++j) {
      const double base = std::abs(first[j]) > 0 ? first[j] : bounds[j].typical;
      const double spread = options.start_spread;
      start[j] = bounds[j].lower >= 0.0 ? std::abs(base) * std::pow(spread, 2.0 * u[j] - 1.0)
                                        : base + spread * std::abs(base) * (2.0 * u[j] - 1.0);
      start[j] = std::clamp(start[j], bounds[j].lower, bounds[j].upper);
    }
    starts.push_back(start);
  }
  result.starts.resize(starts.size());
  std::vector<Eigen::VectorXd> finals(starts.size());
  const int workers = std::max(1, std::min<int>(options.num_workers > 0
                                                    ? options.num_workers
                                                    : static_cast<int>(std::thread::hardware_concurrency()),
                                                static_cast<int>(starts.size())));
  // Ipopt's MUMPS keeps global Fortran state and cannot run in two threads
  // at once, so parallel starts run in worker processes.
  internal::RunTextJobsInWorkers(
      static_cast<int>(starts.size()), workers,
      [&](int i) {
        const std::unique_ptr<FitProblem> problem = make_problem();
        Eigen::VectorXd x;
        const StartOutcome outcome = RunStart(*problem, options, starts[i], i == 0, &x);
        return StartRecordToText({.outcome = outcome, .x = std::vector<double>(x.data(), x.data() + x.size())});
      },
      [&](int i, const std::string& text, const std::string& error, int done) {
        StartOutcome& outcome = result.starts[i];
        if (error.empty()) {
          try {
            StartRecord record = StartRecordFromText(text);
            outcome = std::move(record.outcome);
            finals[i] = Eigen::Map<const Eigen::VectorXd>(record.x.data(), static_cast<Eigen::Index>(record.x.size()));
          } catch (const std::runtime_error& e) {
            outcome.status = std::string("failed: ") + e.what();
          }
        } else {
          outcome.status = "failed: " + error;
        }
        outcome.start = starts[i];
        if (progress)
          progress(0.05 + 0.9 * done / starts.size(),
                   "start " + std::to_string(done) + "/" + std::to_string(starts.size()));
      });

  // 3. The best start, and how many reached it.
  int best = -1;
  for (int i = 0; i < static_cast<int>(starts.size()); ++i)
    if (result.starts[i].success && (best < 0 || result.starts[i].objective < result.starts[best].objective)) best = i;
  if (best < 0) best = ContinueFromBestEndPoint(make_problem, options, result, finals);
  if (options.branch_repair) {
    const std::unique_ptr<FitProblem> problem = make_problem();
    RepairBranches(*problem, options, &result.starts[best], &finals[best]);
  }
  result.best_start = best;
  result.x = finals[best];

  // 4. Covariance in the reduced space.
  const std::unique_ptr<FitProblem> problem = make_problem();
  // The same parameters set the problem's internal scales as in the winning run.
  problem->FeasiblePoint(result.starts[best].scaled_at);
  const Eigen::VectorXd x = result.x;
  const Eigen::VectorXd residuals = problem->WeightedResiduals(x);
  const Eigen::MatrixXd j = problem->ReducedResidualJacobian(x);
  result.chi_square = residuals.squaredNorm();
  result.degrees_of_freedom = std::max(1, problem->num_residuals() - num_parameters);
  result.reduced_chi_square = result.chi_square / result.degrees_of_freedom;
  // Calibrated phasor σ: what the fit leaves beyond them is the residual
  // model error, estimated per harmonic and propagated on its own
  // (model_error.h); otherwise the scatter scales every σ alike when it is
  // worse than stated.
  const Eigen::MatrixXd model_error_information =
      problem->ModelErrorInformation(x, j, result.degrees_of_freedom, &result.model_errors);
  const double variance_scale = result.model_errors.empty() ? std::max(1.0, result.reduced_chi_square) : 1.0;
  const ParameterCovariance covariance =
      SandwichCovariance(j, problem->SharedErrorInformation(j), model_error_information, variance_scale);
  result.covariance = covariance.total;
  const Eigen::VectorXd std = result.covariance.diagonal().cwiseSqrt();
  const Eigen::VectorXd std_model_error = covariance.model_error.diagonal().cwiseMax(0.0).cwiseSqrt();
  result.correlation = std.cwiseInverse().asDiagonal() * result.covariance * std.cwiseInverse().asDiagonal();
  const auto names = initial.Names();
  const auto units = initial.Units();
  const auto& p = result.starts[best].parameters;
  for (int k = 0; k < num_parameters; ++k) {
    result.parameters.push_back({.name = names[k], .unit = units[k], .value = p[k], .std = std[k],
                                 .lower_95 = p[k] - 1.96 * std[k], .upper_95 = p[k] + 1.96 * std[k],
                                 .std_model_error = std_model_error[k]});
    if (std[k] > std::max(std::abs(p[k]), 1e-12))
      result.warnings.push_back(names[k] + " is not identifiable from these data: its standard uncertainty (" +
                                std::to_string(std[k]) + ") exceeds its value");
  }
  if (covariance.collinear)
    result.warnings.push_back("the parameters are nearly collinear: some combination of them is not identifiable");
  result.minima = SummarizeMinima(result.starts, bounds, result.degrees_of_freedom, options.decisive_chi_square_gap);
  result.starts_at_best = result.minima.minima.front().num_starts;
  if (!result.minima.decisive) {
    const LocalMinimum& second = result.minima.minima[1];
    std::string where;
    for (int k = 0; k < num_parameters; ++k)
      where += (k ? ", " : "") + names[k] + " = " + std::to_string(second.parameters[k]);
    result.warnings.push_back("the data do not decide between two fits: a second minimum (" + where +
                              ") is only " + std::to_string(result.minima.second_chi_square_gap) +
                              " worse in chi-square (decisive: " + std::to_string(options.decisive_chi_square_gap) +
                              "); the intervals describe the best one alone");
  }
  result.verdict = JudgeFit(result.reduced_chi_square);
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  if (progress) progress(1.0, "done");
  return result;
}

}  // namespace beamid::solver
