// The frequency-response use case (`beamid frc MODEL`): a model file's
// frequency response curves by harmonic balance and pseudo-arclength
// continuation (stable and unstable branches), one per force level, written
// as PREFIX.csv and PREFIX.json (hb/frc_file.h). A curve that stopped early
// is written too and is an outcome (Incomplete() not empty), not an error.
// Each level's summary is passed to the caller's on_level as its curve is
// done (a curve takes seconds) and kept in the outcome.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "hb/frc_file.h"
#include "solver/workflow/run_observer.h"

namespace beamid::workflow {

struct FrcRequest {
  std::string model_file;                            // docs/model-file.md
  std::vector<double> force_levels_N = {0.5, 1.0, 2.0};  // each 1e-9 .. 1e6
  // 0: not given: 0.9 and 1.1 × the first natural frequency; else 1e-3 ..
  // 1e7 Hz and at most 10 × it, the two different.
  double from_hz = 0.0;
  double to_hz = 0.0;
  int harmonics = 7;     // kept in the balance (1 .. 50)
  int max_points = 3000;  // per curve (2 .. 100000)
  std::string output = "frc";  // prefix of PREFIX.csv and PREFIX.json

  // Throws InputError naming the field (by its command-line option) and the
  // fix: a value out of range, an output that would replace an input
  // (solver/workflow/output_paths.h). The band against the model's first
  // natural frequency is checked once the model is read.
  void Validate() const;
};

// One force level's curve, as the command summarises it.
struct FrcLevelSummary {
  double force_N = 0.0;
  std::size_t num_points = 0;
  int turning_points = 0;
  double peak_theta_rad = 0.0;  // the largest |θ1| on the curve
  double peak_frequency_hz = 0.0;
  bool complete = false;
};

struct FrcOutcome {
  hb::FrcFile file;  // as written
  std::vector<FrcLevelSummary> levels;
  std::string incomplete;  // the curves that stopped early and why ("": none)
  std::string output;

  const std::string& Incomplete() const { return incomplete; }
};

using FrcLevelCallback = std::function<void(const FrcLevelSummary& level)>;

// Validates the request, reads the model, traces each level (one task per
// level, "frc: level 1/3 (0.5 N)"), writes both files and returns them.
FrcOutcome TraceResponseCurves(const FrcRequest& request, const RunObserver& observer = {},
                               const FrcLevelCallback& on_level = {});

}  // namespace beamid::workflow
