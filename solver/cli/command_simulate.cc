// `beamid simulate SCENARIO.json -o DIR`: runs the time-domain simulator
// (hb/stepped_sine.h) through a stepped-sine test and writes the campaign plus
// truth.json (hb/campaign_writer.h). The scenario format: docs/simulator.md.
// The work is workflow::SimulateCampaign; this prints each step and the
// outcome.
#include <chrono>
#include <cstdio>
#include <string>

#include <fmt/core.h>

#include "hb/stepped_sine.h"
#include "solver/cli/cli_output.h"
#include "solver/cli/command_registry.h"
#include "solver/workflow/simulate_campaign.h"

namespace beamid::cli {
namespace {

void RunSimulate(const workflow::SimulateRequest& request, const GlobalOptions& global) {
  workflow::RunObserver observer = CliObserver(global);
  // Text progress is one line per step (a step takes seconds, below); JSON
  // goes through Progress.
  if (!global.JsonProgress()) observer.progress = {};
  const bool step_lines = !global.quiet && !global.JsonProgress();
  const auto start = std::chrono::steady_clock::now();
  const auto print_step = [&](const hb::SimulatedStep& step, int total) {
    if (!step_lines) return;
    const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    PrintToStderr(fmt::format("[{:>4}/{}] {:<10} {:8.3f} Hz  settled in {:5.2f} s{}  ({:.1f} s elapsed)\n",
                              step.index + 1, total, step.level, step.nominal_frequency_hz, step.settle_s,
                              step.settled ? "" : " (NOT settled)", elapsed));
  };
  const workflow::SimulateOutcome outcome = workflow::SimulateCampaign(request, observer, print_step);
  if (!global.quiet) {
    const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    PrintToStderr(fmt::format("wrote {} steps to {} ({:.1f} MB) in {:.1f} s\n", outcome.num_steps, request.output,
               static_cast<double>(outcome.bytes_written) / 1e6, elapsed));
    if (outcome.unsettled_steps > 0)
      PrintToStderr(fmt::format(
          "warning: {} step(s) reached timing.settle_max_s before settling; their recordings still hold a "
          "transient (truth.json marks them \"settled\": false)\n",
          outcome.unsettled_steps));
    if (outcome.clipped_samples > 0)
      PrintToStderr(fmt::format("warning: the ADC clipped {} samples; raise adc_range in the scenario's noise\n",
                 outcome.clipped_samples));
  }
}

BEAMID_REGISTER_COMMAND("simulate", [](CLI::App& app, const GlobalOptions& global) {
  auto request = std::make_shared<workflow::SimulateRequest>();
  CLI::App* command = app.add_subcommand(
      "simulate",
      "Simulate a stepped-sine test in the time domain (finite-element beam, nonlinear support, noise) and write\n"
      "a campaign (campaign.json + one CSV per step) and truth.json (true parameters, noise-free phasors).\n"
      "The scenario format is described in docs/simulator.md.\n\n"
      "Example:\n"
      "  beamid simulate examples/scenarios/paper_base.json -o out/paper_base");
  command->add_option("scenario", request->scenario, "Scenario file (JSON)")->required()->check(CLI::ExistingFile);
  command->add_option("-o,--output", request->output, "Output directory for the campaign")->required();
  command->add_flag("--overwrite", request->overwrite, "Replace a campaign already in the output directory");
  command->callback([request, &global] { RunSimulate(*request, global); });
});

}  // namespace
}  // namespace beamid::cli
