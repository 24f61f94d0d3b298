#include "solver/workflow/simulate_campaign.h"

#include <fmt/core.h>

#include "hb/campaign_writer.h"
#include "hb/scenario.h"
#include "solver/workflow/output_paths.h"

namespace beamid::workflow {

void SimulateRequest::Validate() const { OutputPaths().Input(scenario).OutputFolder("-o", output).Check(); }

SimulateOutcome SimulateCampaign(const SimulateRequest& request, const RunObserver& observer,
                                 const SimulatedStepCallback& on_step) {
  request.Validate();
  const hb::Scenario scenario = hb::ReadScenario(request.scenario);
  hb::SteppedSineSimulation simulation(scenario);
  hb::CampaignWriter writer(simulation, request.output, {.overwrite = request.overwrite});
  SimulateOutcome out{.num_steps = scenario.NumSteps(), .output = request.output};
  ObservedTask progress(observer, "simulate");
  simulation.Run([&](const hb::SimulatedStep& step) {
    writer.Write(step);
    if (!step.settled) ++out.unsettled_steps;
    progress.Update(static_cast<double>(step.index + 1) / out.num_steps,
                    fmt::format("{} {:.3f} Hz", step.level, step.nominal_frequency_hz));
    if (on_step) on_step(step, out.num_steps);
  });
  writer.Finish();
  progress.End();
  out.bytes_written = writer.bytes_written();
  out.clipped_samples = writer.clipped_samples();
  return out;
}

}  // namespace beamid::workflow
