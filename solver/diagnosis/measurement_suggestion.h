// What to measure next when two candidate causes fit the data alike: the
// two refitted models predict every step at any position x on the beam, so
// an accelerometer there would add
//     E[Δχ²](x) = Σ_steps Σ_k |Y_A,k(x) − Y_B,k(x)|² / σ_k(x)²
// to the difference between them (if A is true, the expected χ²_B − χ²_A of
// a channel there; its scatter is 2√E), σ_k(x) = a_k + b_k·|Y_1(x)| the
// noise a real chain has at that step and harmonic — a floor plus a part
// proportional to the channel's signal — fitted to the fitted channels'
// stated σ. The position with the
// largest E[Δχ²] is where to add one; its per-level and per-frequency shares
// say which level and which frequencies carry the difference (more steps
// there, or a longer record). E[Δχ²] > kDecisiveChiSquare (6.63) separates
// the two at 99 %.
#pragma once

#include <string>
#include <vector>

#include "solver/diagnosis/fitted_model.h"
#include "solver/estimation/chi_square.h"
#include "solver/estimation/fit_data.h"

namespace beamid::solver {

struct PositionGain {
  double position_m = 0.0;
  double expected_chi_square_difference = 0.0;
};

struct LevelShare {
  std::string level;
  double share = 0.0;  // of the best position's E[Δχ²]
};

struct MeasurementSuggestion {
  std::string first, second;                 // the two candidates
  std::vector<PositionGain> positions;       // along the beam, ascending
  PositionGain best;                         // the largest
  double current_expected = 0.0;             // the fitted channels' E[Δχ²] (what the data gave)
  std::vector<LevelShare> levels;            // at the best position, campaign order
  // The narrowest band of the steps' frequencies that holds 80 % of the best
  // position's E[Δχ²].
  double focus_low_hz = 0.0, focus_high_hz = 0.0;
  std::string text;                          // what to do, in a test engineer's words
};

struct SuggestionOptions {
  int num_positions = 39;  // x = L·i/(n + 1), i = 1..n
  void Validate() const;
};

// a, b: the two refits (FittedModel of Diagnose's stage 3) on `fit`.
MeasurementSuggestion SuggestMeasurement(const FitData& fit, const FittedModel& a, const std::string& a_name,
                                         const FittedModel& b, const std::string& b_name,
                                         const SuggestionOptions& options = {});

}  // namespace beamid::solver
