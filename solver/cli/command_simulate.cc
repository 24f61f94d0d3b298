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
#include "solver/workflow/serve_plan.h"
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

// --serve: the rig runs the steps a plan file asks for, one at a time.
void RunServe(const workflow::ServeRequest& request, const GlobalOptions& global) {
  const bool step_lines = !global.quiet && !global.JsonProgress();
  if (step_lines)
    PrintToStderr(fmt::format("serving the steps {} asks for into {}\n", request.plan_file, request.output));
  const workflow::ServeOutcome outcome =
      workflow::ServePlan(request, CliObserver(global), [&](const hb::SimulatedStep& step, double rig_time_s) {
        if (step_lines)
          PrintToStderr(fmt::format("{:<10} {:8.3f} Hz  settled {:5.2f} s  -> {}  (rig time {:.1f} s)\n", step.level,
                                    step.nominal_frequency_hz, step.settle_s, step.file, rig_time_s));
      });
  if (!global.quiet)
    PrintToStderr(fmt::format("{}: {} steps, {:.1f} s of settle + record\n",
                              outcome.done ? "the plan is done" : "stopped", outcome.steps, outcome.rig_time_s));
}

BEAMID_REGISTER_COMMAND("simulate", [](CLI::App& app, const GlobalOptions& global) {
  auto request = std::make_shared<workflow::SimulateRequest>();
  auto serve = std::make_shared<workflow::ServeRequest>();
  CLI::App* command = app.add_subcommand(
      "simulate",
      "Simulate a stepped-sine test in the time domain (finite-element beam, nonlinear support, noise) and write\n"
      "a campaign (campaign.json + one CSV per step) and truth.json (true parameters, noise-free phasors).\n"
      "The scenario format is described in docs/simulator.md.\n\n"
      "With --serve the simulator is a rig that runs, one at a time, the steps a plan file of `beamid watch`\n"
      "asks for (docs/watch.md), as a DAQ script would.\n\n"
      "Examples:\n"
      "  beamid simulate examples/scenarios/paper_base.json -o out/paper_base\n"
      "  beamid simulate examples/scenarios/paper_base.json -o out/guided --serve out/plan.json  # beside:\n"
      "  beamid watch out/guided --level low=1 --level mid=4 --level high=9 --band 50 58 --plan out/plan.json");
  command->add_option("scenario", request->scenario, "Scenario file (JSON)")->required()->check(CLI::ExistingFile);
  command->add_option("-o,--output", request->output, "Output directory for the campaign")->required();
  command->add_flag("--overwrite", request->overwrite, "Replace a campaign already in the output directory");
  command->add_option("--serve", serve->plan_file, "Plan file to serve: run the steps it asks for, one at a time")
      ->check(NonEmptyPath());
  command->add_option("--poll", serve->poll_s, "--serve: seconds between looks at the plan")->capture_default_str();
  command->add_option("--idle-timeout", serve->idle_timeout_s, "--serve: stop when no new plan comes for this long [s]")
      ->capture_default_str();
  command->callback([request, serve, &global] {
    if (serve->plan_file.empty()) return RunSimulate(*request, global);
    if (request->overwrite)
      throw InputError("--overwrite: not with --serve. Fix: give --serve an empty or new folder");
    serve->scenario = request->scenario;
    serve->output = request->output;
    RunServe(*serve, global);
  });
});

}  // namespace
}  // namespace beamid::cli
