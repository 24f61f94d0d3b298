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

void RunDiagnose(const workflow::DiagnoseRequest& request, const GlobalOptions& global) {
  const workflow::DiagnoseOutcome outcome = workflow::DiagnoseCampaign(request, CliObserver(global));
  const solver::DiagnosisResult& result = outcome.diagnosis;
  if (global.quiet) return;
  // A missing or failing gnuplot leaves the CSV and the script (the diagnosis is written).
  if (!outcome.curves_problem.empty())
    fmt::print(stderr, "{}\n{} not drawn ({} is there)\n", outcome.curves_problem, request.curves + ".png",
               request.curves + ".csv");
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
  fmt::print("{}\nwrote {}{}\n", result.summary, request.output,
             request.csv_output.empty() ? "" : " and " + request.csv_output);
}

BEAMID_REGISTER_COMMAND("diagnose", [](CLI::App& app, const GlobalOptions& global) {
  auto request = std::make_shared<workflow::DiagnoseRequest>();
  // --fit binds to a list; the request's is unset when none is given.
  auto fit_channels = std::make_shared<std::vector<std::string>>();
  CLI::App* sub = app.add_subcommand(
      "diagnose",
      "Locate where the identified model misses the recordings, name the left-out physics (friction, clamp "
      "compliance, added mass, masses at the instruments, modulus error, support asymmetry, harmonic truncation) by "
      "refitting each and validating on the held-out channels, try pairs when one cause leaves a misfit, say where "
      "to measure when two causes tie, and show the fit.\n"
      "Example: beamid diagnose campaign/ --fit acc1,acc2 --validate acc3 -o diagnosis.json --curves frc");
  sub->add_option("campaign", request->campaign_folder, "Campaign folder (holds campaign.json)")->required();
  sub->add_option("--fit", *fit_channels,
                  "Response channels to fit (default: every sensor neither ignored nor held out)")
      ->delimiter(',');
  sub->add_option("--validate", request->validate_channels, "Held-out channels to predict and compare")
      ->delimiter(',');
  sub->add_option("--candidates", request->candidates, "Physics candidates to try (default: all)")->delimiter(',');
  sub->add_flag("!--no-recording-check", request->recording_check,
                "Do not try the measurement artefacts (sensor gain, phase delay and position per fitted channel, "
                "the acquisition's clock, outlying steps) before the physics");
  AddPhasorInputOptions(sub, &request->phasor_input);
  AddModelHarmonicsOptions(sub, &request->harmonics, &request->fit_harmonics, "Harmonics of the base model");
  AddPhasorUncertaintyOption(sub, &request->phasor_uncertainty);
  sub->add_option("--workers", request->workers, "Parallel refits (0: one per core)")
      ->check(CLI::Range(0, 256))
      ->capture_default_str();
  sub->add_option("--significance", request->significance, "Family-wise significance of naming a cause (0 < α < 1)")
      ->check(FiniteRange(1e-12, 0.5))
      ->capture_default_str();
  sub->add_option("--curves", request->curves,
                  "Write PREFIX.csv with the first-harmonic response of measurements, base and diagnosed model per "
                  "level, and PREFIX.png (gnuplot)")
      ->check(NonEmptyPath());
  sub->add_option("-o,--output", request->output, "Diagnosis file (JSON)")->capture_default_str();
  sub->add_option("--csv", request->csv_output,
                  "Also write the candidate table as CSV for a spreadsheet: base, each candidate in rank order, the "
                  "pairs; χ², AIC, BIC, Λ, p, held-out error, own parameters (docs/diagnose.md)")
      ->check(NonEmptyPath());
  sub->add_option("--result", request->result_file,
                  "result.json of 'beamid identify' on this campaign, named in the diagnosis so that "
                  "'beamid report' shows both")
      ->check(NonEmptyPath());
  sub->callback([request, fit_channels, &global] {
    // No --fit: every sensor neither ignored nor held out.
    request->fit_channels = fit_channels->empty() ? std::nullopt : std::optional(*fit_channels);
    RunDiagnose(*request, global);
  });
});

}  // namespace
}  // namespace beamid::cli
