// The model-backbone use case (`beamid backbone MODEL`): a model file's
// backbone — resonance frequency against amplitude — by exact harmonic
// balance (phase resonance), with the paper's corrected multiple-scales
// backbone beside it for a plain beam on a polynomial support, and each
// sensor's displacement; written as PREFIX.csv and PREFIX.json
// (hb/backbone_file.h). A backbone that stopped early is written too and
// is an outcome (Complete() false), not an error.
#pragma once

#include <string>

#include "hb/backbone.h"
#include "hb/backbone_file.h"
#include "solver/workflow/run_observer.h"

namespace beamid::workflow {

struct TraceBackboneRequest {
  std::string model_file;       // docs/model-file.md
  double min_theta_rad = 1e-5;  // smallest θ amplitude (1e-12 .. 1)
  double max_theta_rad = 2e-2;  // largest θ amplitude (1e-12 .. 1, above the smallest)
  int points = 200;             // number of amplitudes (2 .. 10000)
  int harmonics = 7;            // kept in the balance (1 .. 50)
  std::string output = "backbone";  // prefix of PREFIX.csv and PREFIX.json

  // Throws InputError naming the field (by its command-line option) and the
  // fix: a value out of range, the smallest amplitude not below the largest,
  // an output that would replace an input (solver/workflow/output_paths.h).
  void Validate() const;
};

struct TraceBackboneOutcome {
  hb::BackboneSummary summary;  // the traced points; complete, or why it stopped
  hb::BackboneFile file;        // as written
  std::string output;

  bool Complete() const { return summary.complete; }
};

// Validates the request, reads the model, traces its backbone (the task
// "backbone"), writes both files and returns them.
TraceBackboneOutcome TraceModelBackbone(const TraceBackboneRequest& request, const RunObserver& observer = {});

}  // namespace beamid::workflow
