// beamid diagnose: where the base model misses a campaign, which left-out
// physics explains it (refitting every candidate), and the fit with it.
#include <cstdlib>
#include <filesystem>

#include <fmt/core.h>

#include "signal/campaign.h"
#include "signal/campaign_extractor.h"
#include "signal/phasor_set_io.h"
#include "solver/cli/cli_output.h"
#include "solver/cli/command_registry.h"
#include "solver/cli/output_paths.h"
#include "solver/diagnosis/diagnosis.h"
#include "solver/diagnosis/diagnosis_io.h"
#include "solver/estimation/result_io.h"

namespace beamid::cli {
namespace {

struct DiagnoseCommandOptions {
  std::string campaign_folder;
  std::vector<std::string> fit_channels;
  std::vector<std::string> validate_channels;
  std::vector<std::string> candidates;
  PhasorInput phasor_input;
  int harmonics = 5;
  int fit_harmonics = 3;
  int workers = 0;
  double significance = 0.01;
  bool recording_check = true;
  std::string output = "diagnosis.json";
  std::string curves;  // CSV prefix of the response curves (and its plot)
  std::string result_file;  // identify's result.json, named in the diagnosis for `beamid report`
};

// A gnuplot script, one panel per channel: per level the measured
// first-harmonic amplitude (points), the base model (dashed) and the
// diagnosed model (solid) against frequency.
std::string PlotScript(const solver::DiagnosisResult& result, const std::string& csv, const std::string& png) {
  std::vector<std::string> levels, channels;
  for (const auto& p : result.response) {
    if (std::find(levels.begin(), levels.end(), p.level) == levels.end()) levels.push_back(p.level);
    if (std::find(channels.begin(), channels.end(), p.channel) == channels.end()) channels.push_back(p.channel);
  }
  std::string script = fmt::format(
      "set terminal pngcairo size {},600\nset output '{}'\nset datafile separator ','\nset key top left\n"
      "set xlabel 'frequency [Hz]'\nset ylabel 'first-harmonic amplitude (channel unit)'\n"
      "set multiplot layout 1,{}\n",
      500 * channels.size(), png, channels.size());
  for (const auto& channel : channels) {
    script += fmt::format(
        "set title '{} (points: measured, dashed: base, solid: diagnosed)' noenhanced font ',10'\nplot ", channel);
    for (std::size_t l = 0; l < levels.size(); ++l) {
      const std::string rows =
          fmt::format("\"< awk -F, '$1==\\\"{}\\\" && $3==\\\"{}\\\"' {}\"", levels[l], channel, csv);
      script += fmt::format("{0} using 2:5 with points pt 7 lc {1} title '{2}', "
                            "{0} using 2:7 with lines dt 2 lc {1} notitle, "
                            "{0} using 2:9 with lines dt 1 lc {1} notitle{3}",
                            rows, l + 1, levels[l], l + 1 < levels.size() ? ", \\\n  " : "\n");
    }
  }
  return script + "unset multiplot\n";
}

void RunDiagnose(const DiagnoseCommandOptions& options, const GlobalOptions& global) {
  OutputPaths paths;
  paths.InputFolder(options.campaign_folder)
      .Input(options.phasor_input.phasors_file)
      .Input(options.result_file)
      .Output("-o", options.output);
  if (!options.curves.empty())
    for (const char* suffix : {".csv", ".gp", ".png"})
      paths.Output(std::string("--curves (PREFIX") + suffix + ")", options.curves + suffix);
  paths.Check();
  RequireFitWithinModelHarmonics(options.fit_harmonics, options.harmonics);
  for (const auto& name : options.candidates) {
    const auto names = solver::CandidateNames();
    if (std::find(names.begin() + 1, names.end(), name) == names.end())
      throw std::invalid_argument("--candidates: unknown candidate '" + name +
                                  "' (known: support_friction, clamp_compliance, added_mass, modulus_error, "
                                  "support_asymmetry, harmonic_truncation)");
  }
  const signal::Campaign campaign =
      ReadCampaignForAnalysis(options.campaign_folder, options.fit_channels, options.validate_channels);
  if (!options.result_file.empty()) {
    const std::string mismatch =
        solver::CampaignMismatch(solver::ReadResultFile(options.result_file), campaign.name, options.campaign_folder);
    if (!mismatch.empty())
      throw InputError("--result " + options.result_file + ": " + mismatch +
                       ". Fix: give the result.json that 'beamid identify' wrote for this campaign");
  }
  const signal::PhasorSet phasors =
      ReadOrExtractPhasors(campaign, options.phasor_input, std::max(5, options.fit_harmonics), global);
  const solver::FitData fit = solver::MakeFitData(
      campaign, phasors, {.channels = options.fit_channels, .num_fit_harmonics = options.fit_harmonics});
  const solver::FitData validation =
      options.validate_channels.empty()
          ? solver::FitData{}
          : solver::MakeFitData(campaign, phasors,
                                {.channels = options.validate_channels, .num_fit_harmonics = options.fit_harmonics});
  // The fitted channels examined up to the 5th harmonic (beyond the fitted ones).
  std::vector<std::string> fitted_channels;
  for (const auto& c : fit.channels) fitted_channels.push_back(c.channel);
  const solver::FitData located = solver::MakeFitData(
      campaign, phasors, {.channels = fitted_channels, .num_fit_harmonics = std::max(5, options.fit_harmonics)});
  solver::DiagnosisOptions diagnosis;
  diagnosis.model_harmonics = options.harmonics;
  diagnosis.candidates = options.candidates;
  diagnosis.num_workers = options.workers;
  diagnosis.significance = options.significance;
  diagnosis.measurement_artefacts = options.recording_check;
  Progress progress("diagnose", global);
  const solver::DiagnosisResult result = solver::Diagnose(
      fit, validation, located, diagnosis, [&](double fraction, const std::string&) { progress.Update(fraction); });
  progress.Done();
  // The folder absolute, so that `beamid report` can tell it from another
  // campaign's wherever it runs.
  solver::DiagnosisFile file{
      .diagnosis = result,
      .campaign_folder = std::filesystem::absolute(options.campaign_folder).lexically_normal().string(),
      .campaign_name = campaign.name};
  if (!options.result_file.empty()) {
    file.result_file = std::filesystem::absolute(options.result_file).lexically_normal().string();
  }
  solver::WriteDiagnosisFile(options.output, file);
  if (!options.curves.empty()) {
    const std::string csv = options.curves + ".csv", png = options.curves + ".png", gp = options.curves + ".gp";
    WriteTextFile(csv, solver::ResponseCsv(result));
    WriteTextFile(gp, PlotScript(result, std::filesystem::path(csv).filename().string(),
                                 std::filesystem::path(png).filename().string()));
    const std::string folder = std::filesystem::absolute(gp).parent_path().string();
    const std::string command = "cd '" + folder + "' && gnuplot '" + std::filesystem::path(gp).filename().string() +
                                "' 2>/dev/null";
    if (std::system(command.c_str()) != 0 && !global.quiet)
      PrintToStderr(fmt::format("gnuplot failed or is missing: {} not drawn ({} is there)\n", png, csv));
  }
  if (!global.quiet) {
    fmt::print("diagnosed {} steps in {:.2f} s: {}{}\n", fit.steps.size(), result.seconds, result.verdict,
               result.blame.empty() ? "" : " (to blame: " + result.blame + ")");
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
      if (!c.converged)
        fmt::print("  {:<30} {:>6.2f}  {}\n", c.name, c.signature_score,
                   c.status.starts_with("not refitted") ? c.status : "refit failed (" + c.status + ")");
      else
        fmt::print("  {:<30} {:>6.2f} {:>12.5g} {:>8.3g}x {:>11.5g} {:>10.2g}  {}  ({:.1f} s){}\n", c.name,
                   c.signature_score, c.fit.chi_square, c.residual_drop, c.fit.bic, c.p_value, held_out(c.fit),
                   c.seconds, c.significant ? "  significant" : "");
    fmt::print("{}\nwrote {}\n", result.summary, options.output);
  }
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
  sub->add_option("--fit", options->fit_channels, "Response channels to fit (default: all)")->delimiter(',');
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
