// A fitted model of the diagnosis (the base fit or a candidate's refit from
// a worker's record) rebuilt in the diagnosing process, to predict any
// channel: fitted, held out, or a probe position for the next measurement.
#pragma once

#include <memory>
#include <vector>

#include <Eigen/Core>

#include "solver/estimation/fit_data.h"
#include "solver/estimation/fit_problem.h"
#include "solver/estimation/model_family.h"
#include "solver/estimation/model_structure.h"
#include "solver/estimation/prediction.h"

namespace beamid::solver {

// A fitted model rebuilt in this process: its problem with the internal
// scales of the winning start and the optimiser's variables there, so that
// its phasors at any channel are the fit's own (not a re-solve that could
// land on another branch).
struct FittedModel {
  FitData data;  // what it was fitted to (corrected data for a fault of the recording)
  const ModelFamily* family;
  ModelStructure structure;  // values: the optimum
  std::unique_ptr<FitProblem> problem;
  Eigen::VectorXd x;
  int model_harmonics = 5;

  // structure: the fitted one (its values are replaced by `values`);
  // scaled_at: the parameters whose FeasiblePoint set x's scales.
  FittedModel(const FitData& fit, const ModelFamily& family, const ModelStructure& structure, int model_harmonics,
              const std::vector<double>& scaled_at, Eigen::VectorXd variables, const std::vector<double>& values);

  // Per step, channels × K phasors of `data`'s channels in its units
  // (harmonics the model lacks are 0).
  std::vector<Eigen::MatrixXcd> Phasors(const FitData& at) const;

  // The model as identify would have written it (no covariance): what the
  // families trace curves and backbones from.
  IdentifiedModel Identified() const;

  // |Θ₁|, the first harmonic of the support rotation y'(L) at each step:
  // from the state where the family's state holds Θ (harmonic balance),
  // otherwise from the fitted displacements near the support by the
  // one-sided second-order difference (3y(L) − 4y(L−δ) + y(L−2δ))/(2δ)
  // (multiple scales, whose state is the mode's amplitude).
  std::vector<double> SupportRotationAmplitudes_rad() const;
  // Always by the difference: the check of the state's Θ.
  std::vector<double> SupportRotationAmplitudesFromShape_rad() const;
};

}  // namespace beamid::solver
