// `beamid simulate SCENARIO.json -o DIR`: runs the time-domain simulator
// (hb/stepped_sine.h) through a stepped-sine test and writes the campaign plus
// truth.json (hb/campaign_writer.h). The scenario format: docs/simulator.md.
#include <chrono>
#include <cstdio>
#include <string>

#include <fmt/core.h>

#include "hb/campaign_writer.h"
#include "hb/scenario.h"
#include "hb/stepped_sine.h"
#include "solver/cli/cli_output.h"
#include "solver/cli/command_registry.h"
#include "solver/workflow/output_paths.h"

namespace beamid::cli {
namespace {

struct SimulateOptions {
  std::string scenario;
  std::string output;
  bool overwrite = false;
};

void RunSimulate(const SimulateOptions& options, const GlobalOptions& global) {
  workflow::OutputPaths().Input(options.scenario).OutputFolder("-o", options.output).Check();
  const hb::Scenario scenario = hb::ReadScenario(options.scenario);
  hb::SteppedSineSimulation simulation(scenario);
  hb::CampaignWriter writer(simulation, options.output, {.overwrite = options.overwrite});
  const int total = scenario.NumSteps();
  const auto start = std::chrono::steady_clock::now();
  int unsettled = 0;
  Progress progress("simulate", global);
  // Text progress is one line per step (a step takes seconds); JSON goes
  // through Progress.
  const bool step_lines = !global.quiet && !global.JsonProgress();
  simulation.Run([&](const hb::SimulatedStep& step) {
    writer.Write(step);
    if (!step.settled) ++unsettled;
    if (global.JsonProgress())
      progress.Update(static_cast<double>(step.index + 1) / total,
                      fmt::format("{} {:.3f} Hz", step.level, step.nominal_frequency_hz));
    if (step_lines) {
      const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      PrintToStderr(fmt::format("[{:>4}/{}] {:<10} {:8.3f} Hz  settled in {:5.2f} s{}  ({:.1f} s elapsed)\n", step.index + 1,
                 total, step.level, step.nominal_frequency_hz, step.settle_s, step.settled ? "" : " (NOT settled)",
                 elapsed));
    }
  });
  writer.Finish();
  progress.Done();
  if (!global.quiet) {
    const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    PrintToStderr(fmt::format("wrote {} steps to {} ({:.1f} MB) in {:.1f} s\n", total, options.output,
               static_cast<double>(writer.bytes_written()) / 1e6, elapsed));
    if (unsettled > 0)
      PrintToStderr(fmt::format(
          "warning: {} step(s) reached timing.settle_max_s before settling; their recordings still hold a "
          "transient (truth.json marks them \"settled\": false)\n",
          unsettled));
    if (writer.clipped_samples() > 0)
      PrintToStderr(fmt::format("warning: the ADC clipped {} samples; raise adc_range in the scenario's noise\n",
                 writer.clipped_samples()));
  }
}

BEAMID_REGISTER_COMMAND("simulate", [](CLI::App& app, const GlobalOptions& global) {
  auto options = std::make_shared<SimulateOptions>();
  CLI::App* command = app.add_subcommand(
      "simulate",
      "Simulate a stepped-sine test in the time domain (finite-element beam, nonlinear support, noise) and write\n"
      "a campaign (campaign.json + one CSV per step) and truth.json (true parameters, noise-free phasors).\n"
      "The scenario format is described in docs/simulator.md.\n\n"
      "Example:\n"
      "  beamid simulate examples/scenarios/paper_base.json -o out/paper_base");
  command->add_option("scenario", options->scenario, "Scenario file (JSON)")->required()->check(CLI::ExistingFile);
  command->add_option("-o,--output", options->output, "Output directory for the campaign")->required();
  command->add_flag("--overwrite", options->overwrite, "Replace a campaign already in the output directory");
  command->callback([options, &global] { RunSimulate(*options, global); });
});

}  // namespace
}  // namespace beamid::cli
