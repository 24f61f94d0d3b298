// What a multistart search reports: each start's outcome, and the distinct
// local minima the converged starts reached. Two end points are one minimum
// when their χ² agree to 1e-4 (relative) and every parameter to 1e-3 of its
// scale max(|p|, typical). Whether the data decide between the best two
// minima is judged by the likelihood-ratio gap
//     Δ = (χ²₂ − χ²₁) / max(1, χ²₁/ν),
// the scatter taken from the fit when it is worse than the stated
// uncertainties; below ~9 (3σ for one degree of freedom) the second minimum
// is not ruled out, and its parameters belong beside the best fit's.
#pragma once

#include <string>
#include <vector>

#include "solver/estimation/model_structure.h"

namespace beamid::solver {

constexpr double kDecisiveChiSquareGap = 9.0;

// How a start reached its end point.
enum class StartRoute {
  kMeasuredStates = 0,  // states seeded at the rotation the data show (the measured branch)
  kFeasibleStates = 1,  // states solved by harmonic balance at the start's parameters
};

struct StartOutcome {
  std::vector<double> start;
  std::vector<double> parameters;
  double objective = 0.0;  // ½χ²
  bool success = false;
  int iterations = 0;   // all Ipopt runs of this start together
  std::string status;   // Ipopt's outcome in words
  int status_code = 0;  // Ipopt's ApplicationReturnStatus
  StartRoute route = StartRoute::kMeasuredStates;
  // Times the end point's states were re-seeded on the measured branch and
  // the fit re-run because that lowered the misfit (a step had converged on
  // the other branch of a fold).
  int branch_repairs = 0;
  // The parameters whose FeasiblePoint set the scales of this start's end
  // point: call problem.FeasiblePoint(scaled_at) before using its x.
  std::vector<double> scaled_at;
};

struct LocalMinimum {
  std::vector<double> parameters;
  double chi_square = 0.0;
  int num_starts = 0;  // how many starts ended there
};

struct MinimaSummary {
  std::vector<LocalMinimum> minima;  // best first; empty when no start converged
  double second_chi_square_gap = 0.0;  // Δ above; 0 with fewer than two minima
  bool decisive = true;                // Δ ≥ the threshold, or only one minimum
};

// `degrees_of_freedom` is ν of the best fit.
MinimaSummary SummarizeMinima(const std::vector<StartOutcome>& starts, const std::vector<ParameterBounds>& bounds,
                              int degrees_of_freedom, double decisive_gap = kDecisiveChiSquareGap);

}  // namespace beamid::solver
