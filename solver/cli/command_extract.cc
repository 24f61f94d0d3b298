// beamid extract: the harmonic phasors of every step of a stepped-sine
// campaign (signal/campaign_extractor.h), written as phasors.json (read by
// the fit) and optionally as a CSV table. The work is
// workflow::ExtractCampaign; this prints its outcome.
#include <algorithm>
#include <memory>
#include <string>

#include <fmt/core.h>

#include "solver/cli/cli_output.h"
#include "solver/cli/command_registry.h"
#include "solver/workflow/extract_campaign.h"

namespace beamid::cli {
namespace {

void RunExtract(const workflow::ExtractRequest& request, const GlobalOptions& global) {
  const workflow::ExtractOutcome outcome = workflow::ExtractCampaign(request, CliObserver(global));
  const signal::PhasorSet& set = outcome.phasors;
  if (global.quiet) return;
  double worst_snr_db = 1e300, longest_settling_s = 0.0;
  std::size_t warned = 0, noted = 0;
  for (const auto& step : set.steps) {
    worst_snr_db = std::min(worst_snr_db, step.quality.snr_db);
    longest_settling_s = std::max(longest_settling_s, step.quality.settled_after_s);
    noted += step.quality.notes.empty() ? 0 : 1;
    if (step.quality.warnings.empty()) continue;
    ++warned;
    for (const auto& warning : step.quality.warnings)
      PrintToStderr(fmt::format("beamid extract: warning: {} ({} Hz, {}): {}\n", step.file, step.nominal_frequency_hz,
                 step.level, warning));
  }
  fmt::print("{} steps{}, {} channels, harmonics 1..{}: worst SNR {:.1f} dB, longest transient {:.3f} s, {} steps with "
             "warnings, {} with notes (in {})\nwrote {}{}\n",
             set.steps.size(), set.skipped.empty() ? "" : fmt::format(" ({} skipped)", set.skipped.size()),
             outcome.num_sensors + 1, request.harmonics, worst_snr_db, longest_settling_s, warned, noted,
             request.output, request.output, request.csv_output.empty() ? "" : " and " + request.csv_output);
}

BEAMID_REGISTER_COMMAND("extract", [](CLI::App& app, const GlobalOptions& global) {
  auto request = std::make_shared<workflow::ExtractRequest>();
  CLI::App* sub = app.add_subcommand(
      "extract",
      "Harmonic phasors of every step of a stepped-sine campaign: the transient is dropped, the excitation\n"
      "frequency estimated from the force, and for every channel and harmonic 1..H the complex peak phasor\n"
      "(SI units, referenced so that the force fundamental is real positive) with its standard uncertainty.\n"
      "Example (a simulated campaign):\n"
      "  beamid simulate examples/scenarios/paper_base.json -o out/paper_base\n"
      "  beamid extract out/paper_base -H 5 -o out/phasors.json --csv out/phasors.csv");
  sub->add_option("campaign", request->campaign_folder, "Campaign folder (holds campaign.json)")->required();
  sub->add_option("-H,--harmonics", request->harmonics, "Harmonics per channel")
      ->check(CLI::Range(1, 50))
      ->capture_default_str();
  sub->add_option("-o,--output", request->output, "Phasors file (JSON, format beamid-phasors/1)")
      ->capture_default_str();
  sub->add_option("--csv", request->csv_output, "Also write a CSV table (one row per step, channel, harmonic)")
      ->check(NonEmptyPath());
  sub->add_option("--threads", request->threads, "Worker threads (0: one per core)")
      ->check(CLI::Range(0, 256))
      ->capture_default_str();
  sub->add_option("--channel", request->channels,
                  "Sensors to be analysed (default: all not ignored); problems of the others only warn")
      ->delimiter(',');
  sub->add_flag("--skip-bad-steps", request->skip_bad_steps,
                "Leave out the steps whose recordings hold errors (listed, and kept in the phasors file as "
                "skipped); without it the run stops with the list");
  sub->add_flag("--remove-ringing", request->remove_ringing,
                "Fit the free vibration each frequency step leaves out of the phasors where it is significant "
                "(the step is flagged; see docs/signal.md, step 7)");
  sub->callback([request, &global] { RunExtract(*request, global); });
});

}  // namespace
}  // namespace beamid::cli
