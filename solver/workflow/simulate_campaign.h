// The simulate use case: the time-domain simulator (hb/stepped_sine.h) run
// through a scenario's stepped-sine test (docs/simulator.md), the campaign
// and truth.json written to a folder (hb/campaign_writer.h). Everything
// `beamid simulate` prints is in the outcome, or passed per step to the
// caller's on_step as the step is written (a step takes seconds).
#pragma once

#include <cstdint>
#include <functional>
#include <string>

#include "hb/stepped_sine.h"
#include "solver/workflow/run_observer.h"

namespace beamid::workflow {

struct SimulateRequest {
  std::string scenario;  // the scenario file (JSON)
  std::string output;    // the campaign folder written
  bool overwrite = false;  // replace a campaign already there

  // Throws InputError naming the field (by its command-line option) and the
  // fix: an output that would replace an input or is no folder
  // (solver/workflow/output_paths.h). The scenario is checked as it is read.
  void Validate() const;
};

struct SimulateOutcome {
  int num_steps = 0;
  int unsettled_steps = 0;  // reached timing.settle_max_s before settling (truth.json marks them)
  std::uintmax_t bytes_written = 0;
  int clipped_samples = 0;  // by the simulated ADC
  std::string output;
};

// Called after each step is written, with the step and the number of steps.
using SimulatedStepCallback = std::function<void(const hb::SimulatedStep& step, int num_steps)>;

// Validates the request, simulates (the task "simulate", its progress per
// step with the step's level and frequency), writes the campaign and returns
// what it wrote.
SimulateOutcome SimulateCampaign(const SimulateRequest& request, const RunObserver& observer = {},
                                 const SimulatedStepCallback& on_step = {});

}  // namespace beamid::workflow
