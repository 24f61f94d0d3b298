// The virtual rig as a process of its own, as a DAQ script runs beside
// `beamid watch`: it polls the plan file (docs/test-plan-format.md) and,
// each time its "sequence" grows, runs the step it asks for on the
// time-domain simulator (hb/virtual_rig.h) and writes it into the campaign
// folder; it stops when the plan is done, or when no new plan came for
// idle_timeout_s. It reads nothing but the scenario and the plan file.
#pragma once

#include <functional>
#include <string>

#include "hb/stepped_sine.h"
#include "solver/workflow/run_observer.h"

namespace beamid::workflow {

struct ServeRequest {
  std::string scenario;   // the scenario file (JSON)
  std::string output;     // the campaign folder written
  std::string plan_file;  // the plan the watch writes
  double poll_s = 0.1;
  double idle_timeout_s = 600.0;  // 0: never

  // Throws InputError naming the option and the fix (the output rule;
  // values out of range).
  void Validate() const;
};

struct ServeOutcome {
  int steps = 0;
  double rig_time_s = 0.0;  // settle + record of the steps run
  bool done = false;        // the plan said so; false: the idle timeout
};

// Called after each step is written.
using ServedStepCallback = std::function<void(const hb::SimulatedStep& step, double rig_time_s)>;

ServeOutcome ServePlan(const ServeRequest& request, const RunObserver& observer = {},
                       const ServedStepCallback& on_step = {});

}  // namespace beamid::workflow
