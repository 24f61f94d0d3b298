// A robust identification: one faulty step (a record cut before it settled,
// a glitch, a step on the wrong branch after a jump) pulls an ordinary
// least-squares fit by its whole χ². An outlier test with refit bounds that
// pull. At the ordinary optimum step i's χ²_i over its d_i = 2·C·K weighted
// residuals is an outlier when
//     P(χ²(d_i) ≥ χ²_i / s²) < α / N          (Bonferroni over the N steps),
//     s² = max(1, median_i χ²_i / median χ²(d))  (a robust scale),
// the worst outlier is left out (its pull can make its neighbours look
// outlying too), the fit is repeated from the optimum and the test again on
// what is left. The pull is bounded only when the outliers are few: when
// outliers remain after min(max_rounds, max_outlier_fraction of the steps,
// at least one) steps have been left out, the misfit is the model's or a
// whole channel's, and leaving steps out would hide what `beamid diagnose`
// is to find — the robust fit then declines and says so. The scale s² makes the test loose
// where the whole fit misses, for the same reason.
#pragma once

#include <string>
#include <vector>

#include "solver/estimation/fit_data.h"
#include "solver/estimation/identify.h"
#include "solver/estimation/model_structure.h"

namespace beamid::solver {

struct RobustFitOptions {
  double outlier_probability = 1e-3;  // α: family-wise false-alarm probability over the steps
  double max_outlier_fraction = 0.1;  // more outliers than this (and than one): the model's misfit
  int max_rounds = 5;

  // Throws InputError naming the field, its value and the allowed range.
  void Validate() const;
};

struct OutlyingStep {
  int step = 0;  // index in the ordinary fit's data
  std::string level;
  std::string file;
  double frequency_hz = 0.0;
  double chi_square = 0.0;  // at the fit where it was found
  int num_residuals = 0;
  double tail_probability = 0.0;  // P(χ²(d) ≥ χ²/s²)
  bool unsettled = false;         // the extraction flagged its record as cut before it settled
};

struct RobustFitResult {
  bool applied = false;                 // outliers were left out and the fit repeated
  std::vector<OutlyingStep> outliers;   // found (left out when applied)
  std::string note;                     // what was done, or why not
  FitData data;                         // the data of `fit` (without the outliers when applied)
  IdentifyResult fit;                   // the robust fit (the ordinary one when not applied)
};

// Per step of `data`, χ²_i at the fit's variables x of `problem` (built on `data`).
std::vector<double> StepChiSquares(FitProblem& problem, const Eigen::VectorXd& x);

// The outliers of `chi_squares` (one per step of data) by the test above, and
// the robust scale used.
std::vector<OutlyingStep> FindOutlyingSteps(const FitData& data, const std::vector<double>& chi_squares,
                                            const RobustFitOptions& options);

// Starts from `ordinary` (fitted by `options` on `data`); refits with
// options.num_starts = 0 from the ordinary optimum.
RobustFitResult RobustRefit(const FitData& data, const ModelStructure& structure, const IdentifyResult& ordinary,
                            const IdentifyOptions& options, const RobustFitOptions& robust = {});

// data without the steps listed (their indices in data).
FitData WithoutSteps(const FitData& data, const std::vector<int>& steps);
// Held-out channels of the same campaign (steps in the same order as the
// fit's) without the steps the robust fit left out: those records are the
// faulty ones, and the robust fit's model holds no state there.
FitData WithoutLeftOutSteps(const FitData& held_out, const RobustFitResult& robust);

}  // namespace beamid::solver
