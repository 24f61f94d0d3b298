#include "solver/estimation/robust_fit.h"

#include <algorithm>
#include <cmath>
#include <memory>

#include <fmt/format.h>

#include "hb/option_checks.h"
#include "solver/estimation/chi_square.h"

namespace beamid::solver {
namespace {

// Median of χ²(d), Wilson–Hilferty (to 0.2 % at d = 2, better above).
double ChiSquareMedian(double dof) { return dof * std::pow(1.0 - 2.0 / (9.0 * dof), 3.0); }

double Median(std::vector<double> values) {
  if (values.empty()) return 0.0;
  const std::size_t middle = values.size() / 2;
  std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(middle), values.end());
  return values[middle];
}

std::string Describe(const OutlyingStep& s) {
  return fmt::format("{} {:.4g} Hz (chi-square {:.3g} over {} residuals{})", s.level, s.frequency_hz, s.chi_square,
                     s.num_residuals, s.unsettled ? "; its record was cut before it settled" : "");
}

}  // namespace

void RobustFitOptions::Validate() const {
  using namespace option_checks;
  RequireInRange("RobustFitOptions.outlier_probability", outlier_probability, 1e-12, 0.5);
  RequireInRange("RobustFitOptions.max_outlier_fraction", max_outlier_fraction, 0.0, 0.5);
  RequireInRange("RobustFitOptions.max_rounds", max_rounds, 1, 10);
}

std::vector<double> StepChiSquares(FitProblem& problem, const Eigen::VectorXd& x) {
  const Eigen::VectorXd r = problem.WeightedResiduals(x);
  const int steps = problem.num_steps();
  const Eigen::Index per_step = steps > 0 ? r.size() / steps : 0;
  std::vector<double> chi_squares(static_cast<std::size_t>(steps));
  for (int i = 0; i < steps; ++i) chi_squares[static_cast<std::size_t>(i)] = r.segment(i * per_step, per_step).squaredNorm();
  return chi_squares;
}

std::vector<OutlyingStep> FindOutlyingSteps(const FitData& data, const std::vector<double>& chi_squares,
                                            const RobustFitOptions& options) {
  const int per_step = 2 * static_cast<int>(data.channels.size()) * data.num_fit_harmonics;
  const double scale = std::max(1.0, Median(chi_squares) / ChiSquareMedian(per_step));
  const double limit = options.outlier_probability / static_cast<double>(std::max<std::size_t>(1, chi_squares.size()));
  std::vector<OutlyingStep> outliers;
  for (std::size_t i = 0; i < chi_squares.size(); ++i) {
    const double tail = ChiSquareUpperTail(chi_squares[i] / scale, per_step);
    if (tail >= limit) continue;
    const FitStep& s = data.steps[i];
    outliers.push_back({.step = static_cast<int>(i),
                        .level = s.level,
                        .file = s.file,
                        .frequency_hz = s.FrequencyHz(),
                        .chi_square = chi_squares[i],
                        .num_residuals = per_step,
                        .tail_probability = tail,
                        .unsettled = s.unsettled});
  }
  return outliers;
}

FitData WithoutSteps(const FitData& data, const std::vector<int>& steps) {
  FitData out = data;
  out.steps.clear();
  for (int i = 0; i < static_cast<int>(data.steps.size()); ++i)
    if (std::find(steps.begin(), steps.end(), i) == steps.end()) out.steps.push_back(data.steps[static_cast<std::size_t>(i)]);
  return out;
}

FitData WithoutLeftOutSteps(const FitData& held_out, const RobustFitResult& robust) {
  if (!robust.applied || held_out.steps.empty()) return held_out;
  std::vector<int> steps;
  for (const OutlyingStep& o : robust.outliers) steps.push_back(o.step);
  return WithoutSteps(held_out, steps);
}

RobustFitResult RobustRefit(const FitData& data, const ModelStructure& structure, const IdentifyResult& ordinary,
                            const IdentifyOptions& options, const RobustFitOptions& robust) {
  robust.Validate();
  RobustFitResult out{.applied = false, .outliers = {}, .note = "", .data = data, .fit = ordinary};
  const int allowed = std::max(1, static_cast<int>(robust.max_outlier_fraction * static_cast<double>(data.steps.size())));
  IdentifyOptions refit = options;
  refit.num_starts = 0;
  refit.num_workers = 1;
  // From the optimum a refit converges in a few iterations or not at all:
  // ipopt.max_iterations, not the first start's long allowance (a refit of a
  // model missing physics ran 1000 iterations, two minutes, to fail).
  refit.continuation_iterations = 0;
  refit.first_start_min_iterations = 0;

  std::vector<int> kept(data.steps.size());  // current step → ordinary step
  for (std::size_t i = 0; i < kept.size(); ++i) kept[i] = static_cast<int>(i);
  FitData current = data;
  IdentifyResult fit = ordinary;
  // The steps one may leave out; outliers beyond them are the model's or a
  // channel's (header).
  const int budget = std::min(allowed, robust.max_rounds);
  for (;;) {
    const std::unique_ptr<FitProblem> problem = options.family->MakeProblem(current, structure, options.model);
    problem->FeasiblePoint(fit.starts[static_cast<std::size_t>(fit.best_start)].scaled_at);
    std::vector<OutlyingStep> found = FindOutlyingSteps(current, StepChiSquares(*problem, fit.x), robust);
    if (found.empty()) break;
    // The pulled fit makes neighbours of a faulty step look outlying too:
    // only when outliers remain after the budget's worth of steps has been
    // left out one at a time is the misfit no faulty step.
    if (static_cast<int>(out.outliers.size()) >= budget) {
      const std::size_t remaining = found.size();
      for (auto& s : found) s.step = kept[static_cast<std::size_t>(s.step)];
      out.outliers.insert(out.outliers.end(), found.begin(), found.end());
      out.note = fmt::format(
          "{} of {} steps miss beyond the noise ({} still after leaving out the worst {}): a misfit spread over that "
          "many steps is no faulty step but the model's or a whole channel's (a sensor's calibration, position or "
          "delay); no step was left out (run 'beamid diagnose', which checks both)",
          out.outliers.size(), data.steps.size(), remaining, out.outliers.size() - remaining);
      out.applied = false;
      out.data = data;
      out.fit = ordinary;
      return out;
    }
    // Only the worst: its pull can make its neighbours look outlying too.
    OutlyingStep worst = *std::max_element(found.begin(), found.end(), [](const OutlyingStep& a, const OutlyingStep& b) {
      return a.chi_square < b.chi_square;
    });
    worst.step = kept[static_cast<std::size_t>(worst.step)];
    out.outliers.push_back(worst);
    std::vector<int> left_out;
    for (const auto& s : out.outliers) left_out.push_back(s.step);
    std::sort(left_out.begin(), left_out.end());
    current = WithoutSteps(data, left_out);
    kept.clear();
    for (int i = 0; i < static_cast<int>(data.steps.size()); ++i)
      if (!std::binary_search(left_out.begin(), left_out.end(), i)) kept.push_back(i);
    std::vector<double> start;
    for (const auto& p : fit.parameters) start.push_back(p.value);
    ModelStructure from = structure;
    from.SetValues(start);
    try {
      fit = IdentifyWith([&] { return refit.family->MakeProblem(current, from, refit.model); }, from, start, refit);
    } catch (const std::runtime_error& e) {
      out = {.applied = false,
             .outliers = out.outliers,
             .note = std::string("the refit without the outlying steps failed (") + e.what() +
                     "); no step was left out",
             .data = data,
             .fit = ordinary};
      return out;
    }
    out.applied = true;
  }
  if (out.applied) {
    out.data = current;
    out.fit = fit;
    std::string list;
    for (const auto& s : out.outliers) list += (list.empty() ? "" : "; ") + Describe(s);
    out.note = fmt::format("left out {} outlying step(s) and refitted: {}", out.outliers.size(), list);
  }
  return out;
}

}  // namespace beamid::solver
