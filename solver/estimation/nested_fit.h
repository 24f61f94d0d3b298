// The plain nested approach, kept as the baseline that `Identify` is
// measured against (tests/benchmarks/identification_benchmark.cc): for each trial parameter set, solve
// the harmonic balance of every step by Newton (warm-started along each
// sweep), then take a Levenberg–Marquardt step on the parameters with a
// forward-difference Jacobian — one full set of step solves per parameter.
#pragma once

#include <vector>

#include "solver/estimation/fit_data.h"
#include "solver/estimation/identification_problem.h"
#include "solver/estimation/model_structure.h"

namespace beamid::solver {

struct NestedFitOptions {
  ModelOptions model;
  int max_iterations = 100;
  double relative_tolerance = 1e-8;  // on the change of χ² and of the parameters

  // Throws InputError naming the field, its value and the allowed range.
  void Validate() const;
};

struct NestedFitResult {
  std::vector<double> parameters;
  double chi_square = 0.0;
  int iterations = 0;
  int step_solves = 0;  // harmonic-balance solves of one step
  bool converged = false;
};

NestedFitResult NestedFit(const FitData& data, const ModelStructure& structure, const std::vector<double>& start,
                          const NestedFitOptions& options = {});

}  // namespace beamid::solver
