// Gauss–Newton in the parameters alone, the states of every trial solved by
// the balance: the finish of a fit that Ipopt leaves short of its tolerance
// near the optimum (seen on a slipping support balanced with 21 harmonics:
// Ipopt circles the optimum, χ² jittering by a few tenths and the balance's
// residual staying near 1e-7 N·m). What matters there is whether χ² could
// still fall by what the data resolve, and the Gauss–Newton decrement
//     δ = χ²(p) − ‖r + J·Δp‖²,   Δp = −J⁺·r
// (r the whitened residuals, J their reduced Jacobian at p) answers it: at
// most kStationaryDecrement·s², s² = max(1, χ²/ν) the scale of the misfit,
// the linearised optimum lies within a third of one standard deviation of
// p (Δχ² = s² is one σ along any direction).
#pragma once

#include <optional>
#include <vector>

#include <Eigen/Core>

#include "solver/estimation/fit_problem.h"
#include "solver/estimation/model_structure.h"

namespace beamid::solver {

inline constexpr double kStationaryDecrement = 0.1;
inline constexpr int kPolishSteps = 8;

// The step −J⁺·r, with every parameter it would carry through a bound (a
// damping coefficient the fit put at 0 that the step wants below) moved onto
// that bound and held there, and the others' step solved for the rest: at a
// bound with its gradient pointing out, such a parameter is stationary, and
// the others' step is the question. p and bounds in J's column order.
Eigen::VectorXd BoundedGaussNewtonStep(const Eigen::MatrixXd& jacobian, const Eigen::VectorXd& residuals,
                                       const std::vector<double>& p, const std::vector<ParameterBounds>& bounds);

struct PolishedPoint {
  std::vector<double> parameters;
  Eigen::VectorXd x;  // the problem's variables there, the states solved (scaled at `parameters`)
  double chi_square = 0.0;
  double decrement = 0.0;  // δ at the point
};

// Up to kPolishSteps steps from `start` (each halved up to four times until
// χ² falls), until δ ≤ kStationaryDecrement·s²; nothing when a balance
// fails or χ² stops falling first. Leaves `problem` scaled at the point
// returned.
std::optional<PolishedPoint> PolishInReducedSpace(FitProblem& problem, const std::vector<double>& start);

}  // namespace beamid::solver
