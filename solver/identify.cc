#include "solver/identify.h"

#include "solver/internal/ipopt_program.h"
#include "solver/internal/worker_processes.h"
#include "solver/multiple_scales_problem.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <random>
#include <thread>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>

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

// The first start (the direct estimate, or the caller's own start) is the one
// a single-start fit rests on, and from a factor 3 away it may need ~400
// iterations; the further starts are exploratory and keep the cap, because a
// start on another branch of the response stalls rather than converges.
constexpr int kFirstStartMaxIterations = 1000;

StartOutcome RunStart(FitProblem& problem, const IdentifyOptions& options, const std::vector<double>& start,
                      bool first, Eigen::VectorXd* x_out) {
  const Eigen::VectorXd x0 = problem.FeasiblePoint(start);
  internal::IpoptOptions ipopt = options.ipopt;
  if (first) ipopt.max_iterations = std::max(ipopt.max_iterations, kFirstStartMaxIterations);
  const internal::IpoptOutcome outcome = internal::RunIpopt(problem, x0, ipopt);
  StartOutcome result{.start = start,
                      .parameters = problem.Parameters(outcome.x),
                      .objective = problem.Objective(outcome.x),
                      .success = outcome.success,
                      .iterations = outcome.iterations,
                      .status = outcome.status_text,
                      .status_code = outcome.status};
  if (x_out) *x_out = outcome.x;
  return result;
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
  IdentifyResult result =
      IdentifyWith([&] { return make_problem(bounded); }, bounded, first, options, progress);
  result.direct = direct;
  return result;
}

}  // namespace

IdentifyResult Identify(const FitData& data, const ModelStructure& structure, const IdentifyOptions& options,
                        const ProgressCallback& progress) {
  return IdentifyFromDirectEstimate(
      [&](const ModelStructure& bounded) {
        return std::make_unique<IdentificationProblem>(data, bounded, options.model);
      },
      data, structure, options, progress);
}

IdentifyResult IdentifyMultipleScales(const FitData& data, const ModelStructure& structure,
                                      const IdentifyOptions& options, const ProgressCallback& progress) {
  const MultipleScalesProblemOptions model{.beam_loss_factor = options.model.beam_loss_factor};
  // What the model cannot hold (sensor masses, harmonics above 3) is bad
  // input: refuse it here, not as a failure of every start.
  { const MultipleScalesProblem check(data, structure, model); }
  return IdentifyFromDirectEstimate(
      [&](const ModelStructure& bounded) { return std::make_unique<MultipleScalesProblem>(data, bounded, model); },
      data, structure, options, progress);
}

IdentifyResult IdentifyWith(const ProblemFactory& make_problem, const ModelStructure& structure,
                            const std::vector<double>& first, const IdentifyOptions& options,
                            const ProgressCallback& progress) {
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
  const int workers = std::max(1, std::min<int>(options.num_threads > 0
                                                    ? options.num_threads
                                                    : static_cast<int>(std::thread::hardware_concurrency()),
                                                static_cast<int>(starts.size())));
  // Ipopt's MUMPS keeps global Fortran state and cannot run in two threads
  // at once, so parallel starts run in worker processes.
  internal::RunInWorkers(
      static_cast<int>(starts.size()), workers,
      [&](int i) {
        const std::unique_ptr<FitProblem> problem = make_problem();
        Eigen::VectorXd x;
        const StartOutcome outcome = RunStart(*problem, options, starts[i], i == 0, &x);
        // Worker processes send doubles: the Ipopt status travels as its code.
        std::vector<double> record = {outcome.objective, outcome.success ? 1.0 : 0.0,
                                      static_cast<double>(outcome.iterations),
                                      static_cast<double>(outcome.status_code)};
        record.insert(record.end(), outcome.parameters.begin(), outcome.parameters.end());
        record.insert(record.end(), x.data(), x.data() + x.size());
        return record;
      },
      [&](int i, const std::vector<double>& record, const std::string& error, int done) {
        StartOutcome& outcome = result.starts[i];
        outcome.start = starts[i];
        if (!error.empty()) {
          outcome.status = "failed: " + error;
        } else {
          outcome.objective = record[0];
          outcome.success = record[1] != 0.0;
          outcome.iterations = static_cast<int>(record[2]);
          outcome.status_code = static_cast<int>(record[3]);
          outcome.status = internal::IpoptStatusText(outcome.status_code);
          constexpr int kHead = 4;
          outcome.parameters.assign(record.begin() + kHead, record.begin() + kHead + num_parameters);
          finals[i] = Eigen::Map<const Eigen::VectorXd>(
              record.data() + kHead + num_parameters, static_cast<Eigen::Index>(record.size()) - kHead - num_parameters);
        }
        if (progress)
          progress(0.05 + 0.9 * done / starts.size(),
                   "start " + std::to_string(done) + "/" + std::to_string(starts.size()));
      });

  // 3. The best start, and how many reached it.
  int best = -1;
  for (int i = 0; i < static_cast<int>(starts.size()); ++i)
    if (result.starts[i].success && (best < 0 || result.starts[i].objective < result.starts[best].objective)) best = i;
  if (best < 0) {
    std::string why = result.starts[0].status;
    throw std::runtime_error("no start converged (first start: " + why + ")");
  }
  result.best_start = best;
  const double best_objective = result.starts[best].objective;
  for (const auto& s : result.starts)
    if (s.success && s.objective <= best_objective * (1.0 + 1e-4) + 1e-9) ++result.starts_at_best;
  result.x = finals[best];

  // 4. Covariance in the reduced space.
  const std::unique_ptr<FitProblem> problem = make_problem();
  // The same start sets the problem's internal scales as in the winning run.
  problem->FeasiblePoint(starts[best]);
  const Eigen::VectorXd x = result.x;
  const Eigen::VectorXd residuals = problem->WeightedResiduals(x);
  const Eigen::MatrixXd j = problem->ReducedResidualJacobian(x);
  result.chi_square = residuals.squaredNorm();
  result.degrees_of_freedom = std::max(1, problem->num_residuals() - num_parameters);
  result.reduced_chi_square = result.chi_square / result.degrees_of_freedom;
  const double variance_scale = std::max(1.0, result.reduced_chi_square);
  // Inverted scale-free (unit diagonal, the correlation's inverse): in
  // physical units the diagonal spans 20 orders of magnitude (k3 in
  // N·m/rad³ beside a clamp compliance in rad/(N·m)), beyond double
  // precision, and rounding made eigenvalues of well-determined
  // directions negative (intervals of ±1e143).
  const Eigen::MatrixXd information = j.transpose() * j;
  const Eigen::VectorXd scale = information.diagonal().cwiseSqrt().cwiseMax(1e-300);
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> normalised(scale.cwiseInverse().asDiagonal() * information *
                                                            scale.cwiseInverse().asDiagonal());
  const Eigen::VectorXd values = normalised.eigenvalues().cwiseMax(1e-300);
  result.covariance = variance_scale * scale.cwiseInverse().asDiagonal() * normalised.eigenvectors() *
                      values.cwiseInverse().asDiagonal() * normalised.eigenvectors().transpose() *
                      scale.cwiseInverse().asDiagonal();
  const Eigen::VectorXd std = result.covariance.diagonal().cwiseSqrt();
  result.correlation = std.cwiseInverse().asDiagonal() * result.covariance * std.cwiseInverse().asDiagonal();
  const auto names = initial.Names();
  const auto units = initial.Units();
  const auto& p = result.starts[best].parameters;
  for (int k = 0; k < num_parameters; ++k) {
    result.parameters.push_back({.name = names[k], .unit = units[k], .value = p[k], .std = std[k],
                                 .lower_95 = p[k] - 1.96 * std[k], .upper_95 = p[k] + 1.96 * std[k]});
    if (std[k] > std::max(std::abs(p[k]), 1e-12))
      result.warnings.push_back(names[k] + " is not identifiable from these data: its standard uncertainty (" +
                                std::to_string(std[k]) + ") exceeds its value");
  }
  // Collinearity on the scale-free information matrix.
  if (normalised.eigenvalues().minCoeff() < 1e-8 * normalised.eigenvalues().maxCoeff())
    result.warnings.push_back("the parameters are nearly collinear: some combination of them is not identifiable");
  if (result.reduced_chi_square > 4.0)
    result.warnings.push_back("the fit is worse than the phasor uncertainties allow (reduced chi-square " +
                              std::to_string(result.reduced_chi_square) + "): run 'beamid diagnose'");
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  if (progress) progress(1.0, "done");
  return result;
}

}  // namespace beamid::solver
