// beamid diagnose: where the base model misses a campaign, which left-out
// physics explains it (refitting every candidate), and the fit with it. The
// work is workflow::DiagnoseCampaign; this file parses the options and prints
// the outcome.
#include <cmath>
#include <optional>

#include <fmt/core.h>
#include <fmt/ranges.h>

#include "solver/cli/cli_output.h"
#include "solver/cli/command_registry.h"
#include "solver/diagnosis/diagnosis.h"
#include "solver/workflow/diagnose_campaign.h"

namespace beamid::cli {
namespace {

struct DiagnoseCommandOptions {
  std::string campaign_folder;
  std::vector<std::string> fit_channels;
  std::vector<std::string> validate_channels;
  std::vector<std::string> candidates;
  workflow::PhasorInput phasor_input;
  int harmonics = 5;
  int fit_harmonics = 3;
  int workers = 0;
  double significance = 0.01;
  bool recording_check = true;
  std::string output = "diagnosis.json";
  std::string curves;  // CSV prefix of the response curves (and its plot)
  std::string result_file;  // identify's result.json, named in the diagnosis for `beamid report`
};

void RunDiagnose(const DiagnoseCommandOptions& options, const GlobalOptions& global) {
  const workflow::DiagnoseRequest request{
      .campaign_folder = options.campaign_folder,
      // No --fit: every sensor neither ignored nor held out.
      .fit_channels = options.fit_channels.empty() ? std::nullopt : std::optional(options.fit_channels),
      .validate_channels = options.validate_channels,
      .candidates = options.candidates,
      .phasor_input = options.phasor_input,
      .harmonics = options.harmonics,
      .fit_harmonics = options.fit_harmonics,
      .workers = options.workers,
      .significance = options.significance,
      .recording_check = options.recording_check,
      .output = options.output,
      .curves = options.curves,
      .result_file = options.result_file};
  const workflow::DiagnoseOutcome outcome = workflow::DiagnoseCampaign(request, CliObserver(global));
  const solver::DiagnosisResult& result = outcome.diagnosis;
  if (global.quiet) return;
  // A missing or failing gnuplot leaves the CSV and the script (the diagnosis is written).
  if (!outcome.curves_problem.empty())
    fmt::print(stderr, "{}\n{} not drawn ({} is there)\n", outcome.curves_problem, options.curves + ".png",
               options.curves + ".csv");
  fmt::print("diagnosed {} steps in {:.2f} s: {}{}\n", outcome.num_steps, result.seconds,
             solver::ToString(result.verdict),
             result.blame == solver::Blame::kNone ? "" : " (to blame: " + solver::ToString(result.blame) + ")");
  fmt::print("  {:<30} {:>6} {:>12} {:>9} {:>11} {:>10}  {} / {}\n", "candidate", "score", "chi-square", "drop",
             "BIC", "p", "held-out h1", "chi-square");
  // Without a held-out channel there is no held-out error: say so, not "nan %".
  const auto held_out = [](const solver::FitSummary& summary) {
    if (!std::isfinite(summary.held_out_h1_relative_error)) return std::string("(no held-out channel)");
    return fmt::format("{:.3g} % / {:.4g}", 100.0 * summary.held_out_h1_relative_error, summary.held_out_chi_square);
  };
  fmt::print("  {:<30} {:>6} {:>12.5g} {:>9} {:>11.5g} {:>10}  {}\n", "(base)", "", result.base.chi_square, "",
             result.base.bic, "", held_out(result.base));
  for (const auto& c : result.candidates)
    if (c.status == solver::RefitStatus::kNotRefitted)
      fmt::print("  {:<30} {:>6.2f}  not refitted: {}\n", c.name, c.signature_score, c.status_message);
    else if (c.status == solver::RefitStatus::kFailed)
      fmt::print("  {:<30} {:>6.2f}  refit failed{}\n", c.name, c.signature_score,
                 c.status_message.empty() ? "" : " (" + c.status_message + ")");
    else
      fmt::print("  {:<30} {:>6.2f} {:>12.5g} {:>8.3g}x {:>11.5g} {:>10.2g}  {}  ({:.1f} s){}\n", c.name,
                 c.signature_score, c.fit.chi_square, c.residual_drop, c.fit.bic, c.p_value, held_out(c.fit),
                 c.seconds, c.significant ? "  significant" : "");
  if (!result.final_damping_laws.empty()) {
    fmt::print("the selected model ({}):\n", fmt::join(result.selected, " + "));
    PrintDampingLaws(result.final_damping_laws);
  }
  fmt::print("{}\nwrote {}\n", result.summary, options.output);
}

BEAMID_REGISTER_COMMAND("diagnose", [](CLI::App& app, const GlobalOptions& global) {
  auto options = std::make_shared<DiagnoseCommandOptions>();
  CLI::App* sub = app.add_subcommand(
      "diagnose",
      "Locate where the identified model misses the recordings, name the left-out physics (friction, clamp "
      "compliance, added mass, masses at the instruments, modulus error, support asymmetry, harmonic truncation) by "
      "refitting each and validating on the held-out channels, try pairs when one cause leaves a misfit, say where "
      "to measure when two causes tie, and show the fit.\n"
      "Example: beamid diagnose campaign/ --fit acc1,acc2 --validate acc3 -o diagnosis.json --curves frc");
  sub->add_option("campaign", options->campaign_folder, "Campaign folder (holds campaign.json)")->required();
  sub->add_option("--fit", options->fit_channels,
                  "Response channels to fit (default: every sensor neither ignored nor held out)")
      ->delimiter(',');
  sub->add_option("--validate", options->validate_channels, "Held-out channels to predict and compare")
      ->delimiter(',');
  sub->add_option("--candidates", options->candidates, "Physics candidates to try (default: all)")->delimiter(',');
  sub->add_flag("!--no-recording-check", options->recording_check,
                "Do not try the measurement artefacts (sensor gain, phase delay and position per fitted channel, "
                "the acquisition's clock, outlying steps) before the physics");
  AddPhasorInputOptions(sub, &options->phasor_input);
  AddModelHarmonicsOptions(sub, &options->harmonics, &options->fit_harmonics, "Harmonics of the base model");
  sub->add_option("--workers", options->workers, "Parallel refits (0: one per core)")
      ->check(CLI::Range(0, 256))
      ->capture_default_str();
  sub->add_option("--significance", options->significance, "Family-wise significance of naming a cause (0 < α < 1)")
      ->check(FiniteRange(1e-12, 0.5))
      ->capture_default_str();
  sub->add_option("--curves", options->curves,
                  "Write PREFIX.csv with the first-harmonic response of measurements, base and diagnosed model per "
                  "level, and PREFIX.png (gnuplot)")
      ->check(NonEmptyPath());
  sub->add_option("-o,--output", options->output, "Diagnosis file (JSON)")->capture_default_str();
  sub->add_option("--result", options->result_file,
                  "result.json of 'beamid identify' on this campaign, named in the diagnosis so that "
                  "'beamid report' shows both")
      ->check(NonEmptyPath());
  sub->callback([options, &global] { RunDiagnose(*options, global); });
});

}  // namespace
}  // namespace beamid::cli
