#include "solver/workflow/serve_plan.h"

#include <chrono>
#include <filesystem>
#include <optional>
#include <thread>

#include "hb/errors.h"
#include "hb/option_checks.h"
#include "hb/scenario.h"
#include "hb/virtual_rig.h"
#include "solver/live/test_plan_io.h"
#include "solver/workflow/output_paths.h"

namespace beamid::workflow {

void ServeRequest::Validate() const {
  option_checks::RequireInRange("--poll", poll_s, 1e-3, 3600.0);
  option_checks::RequireInRange("--idle-timeout", idle_timeout_s, 0.0, 1e7);
  OutputPaths().Input(scenario).Input(plan_file).OutputFolder("-o", output).Check();
}

ServeOutcome ServePlan(const ServeRequest& request, const RunObserver& observer, const ServedStepCallback& on_step) {
  request.Validate();
  std::optional<hb::VirtualRig> rig;
  try {
    rig.emplace(hb::ReadScenario(request.scenario), request.output);
  } catch (const InputError&) {
    throw;
  } catch (const std::invalid_argument& e) {  // the scenario's physics, or a folder that holds a campaign
    throw InputError(request.output, "", e.what(), "give an empty folder and a consistent scenario");
  }
  ServeOutcome outcome;
  int acted_on = 0;
  auto last_plan = std::chrono::steady_clock::now();
  for (;;) {
    std::optional<solver::TestPlan> plan;
    std::error_code error;
    // The watch replaces the file atomically: a plan that cannot be read is
    // not half written but wrong, and is an error.
    if (std::filesystem::exists(request.plan_file, error)) plan = solver::ReadTestPlan(request.plan_file);
    if (plan && plan->sequence > acted_on) {
      acted_on = plan->sequence;
      last_plan = std::chrono::steady_clock::now();
      if (plan->done || !plan->next) {
        outcome.done = true;
        break;
      }
      const solver::PlannedStep& next = *plan->next;
      try {
        const hb::SimulatedStep& step = rig->Run(next.level, next.frequency_hz, next.settle_s, next.record_s);
        ++outcome.steps;
        if (on_step) on_step(step, rig->rig_time_s());
      } catch (const std::invalid_argument& e) {
        throw InputError(request.plan_file, "", std::string("the rig cannot run the planned step: ") + e.what(),
                         "plan with the scenario's levels");
      }
      continue;
    }
    const double idle = std::chrono::duration<double>(std::chrono::steady_clock::now() - last_plan).count();
    if (request.idle_timeout_s > 0.0 && idle > request.idle_timeout_s) {
      observer.Warn("serve", "no new plan for " + std::to_string(request.idle_timeout_s) + " s: stopped");
      break;
    }
    std::this_thread::sleep_for(std::chrono::duration<double>(request.poll_s));
  }
  if (outcome.steps > 0) rig->Finish();  // truth.json of the steps run
  outcome.rig_time_s = rig->rig_time_s();
  return outcome;
}

}  // namespace beamid::workflow
