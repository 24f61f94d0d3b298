// The fitted model's phasors in the layout and units of the measurements
// (FitStep::measured): per step a channels × K matrix of harmonics 1..K of
// each channel's quantity, Y = (ikω)^d · y_k from the model's displacement
// phasors y_k at the channel's position (d = the channel's derivative
// order). Harmonics above the model's H are 0. Used to compare a fit with
// any channel set — the fitted ones, held-out ones, more harmonics.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "solver/estimation/fit_data.h"
#include "solver/estimation/fit_problem.h"

namespace beamid::solver {

// `data` must have the steps of the problem's data, in the same order.
std::vector<Eigen::MatrixXcd> ModelPhasors(const FitData& data, FitProblem& problem,
                                           const Eigen::VectorXd& x);

}  // namespace beamid::solver
