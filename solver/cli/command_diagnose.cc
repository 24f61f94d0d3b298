// beamid diagnose: where the base model misses a campaign, which left-out
// physics explains it (refitting every candidate), and the fit with it.
#include <algorithm>
#include <complex>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <fmt/core.h>
#include <fmt/ranges.h>

#include "signal/campaign.h"
#include "signal/campaign_extractor.h"
#include "signal/campaign_identity.h"
#include "signal/phasor_set_io.h"
#include "solver/cli/cli_output.h"
#include "solver/cli/command_registry.h"
#include "solver/cli/output_paths.h"
#include "solver/diagnosis/diagnosis.h"
#include "solver/diagnosis/diagnosis_io.h"
#include "solver/estimation/result_io.h"
#include "solver/report/external_program.h"
#include "solver/report/gnuplot_script.h"
#include "solver/report/temp_folder.h"

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
// diagnosed model (solid) against frequency. The numbers go in as one
// datablock per level and channel; labels and names only as quoted texts
// (GnuplotText), so none can become a gnuplot command. The PNG goes to
// standard output: the script names no file.
std::string PlotScript(const solver::DiagnosisResult& result) {
  std::vector<std::string> levels, channels;
  for (const auto& p : result.response) {
    if (std::find(levels.begin(), levels.end(), p.level) == levels.end()) levels.push_back(p.level);
    if (std::find(channels.begin(), channels.end(), p.channel) == channels.end()) channels.push_back(p.channel);
  }
  std::string script = fmt::format(
      "# Draws PREFIX.png of beamid diagnose --curves on standard output: gnuplot PREFIX.gp > PREFIX.png\n"
      "set terminal pngcairo size {},600 enhanced\nset key top left\n"
      "set xlabel 'frequency [Hz]'\nset ylabel 'first-harmonic amplitude (channel unit)'\n",
      500 * std::max<std::size_t>(channels.size(), 1));
  for (std::size_t c = 0; c < channels.size(); ++c)
    for (std::size_t l = 0; l < levels.size(); ++l) {
      std::vector<std::vector<double>> rows;  // frequency, measured, base, diagnosed
      for (const auto& p : result.response)
        if (p.level == levels[l] && p.channel == channels[c])
          rows.push_back({p.frequency_hz, std::abs(p.measured), std::abs(p.base_model), std::abs(p.final_model)});
      script += solver::Datablock(fmt::format("c{}_l{}", c, l), rows);
    }
  script += fmt::format("set multiplot layout 1,{}\n", std::max<std::size_t>(channels.size(), 1));
  for (std::size_t c = 0; c < channels.size(); ++c) {
    script += fmt::format("set title {} font ',10'\nplot ",
                          solver::GnuplotText(channels[c] + " (points: measured, dashed: base, solid: diagnosed)"));
    for (std::size_t l = 0; l < levels.size(); ++l)
      script += fmt::format("$c{0}_l{1} using 1:2 with points pt 7 lc {2} title {3}, "
                            "$c{0}_l{1} using 1:3 with lines dt 2 lc {2} notitle, "
                            "$c{0}_l{1} using 1:4 with lines dt 1 lc {2} notitle{4}",
                            c, l, l + 1, solver::GnuplotText(levels[l]), l + 1 < levels.size() ? ", \\\n  " : "\n");
  }
  return script + "unset multiplot\n";
}

std::string ReadWholeFile(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// Draws PREFIX.png with gnuplot, run without a shell; the PNG is written like
// every other output (whole or not at all). A missing or failing gnuplot
// leaves the CSV and the script and says so (the diagnosis is written).
void DrawCurves(const std::string& script, const std::string& png, const std::string& csv, const GlobalOptions& global) {
  std::string problem;
  try {
    const solver::TempFolder folder("gnuplot");
    const std::filesystem::path picture = folder.path() / "curves.png", messages = folder.path() / "gnuplot.err";
    const int status = solver::RunExternalProgram({.program = "gnuplot",
                                                   .debian_package = "gnuplot-nox",
                                                   .stdin_text = script,
                                                   .stdout_file = picture,
                                                   .stderr_file = messages});
    const std::string bytes = ReadWholeFile(picture);
    if (status == 0 && !bytes.empty()) WriteTextFile(png, bytes);
    else problem = fmt::format("gnuplot failed (exit status {}): {}", status, ReadWholeFile(messages).substr(0, 2000));
  } catch (const EnvironmentError& e) {
    problem = e.what();
  }
  if (!problem.empty() && !global.quiet) fmt::print(stderr, "{}\n{} not drawn ({} is there)\n", problem, png, csv);
}

void RunDiagnose(const DiagnoseCommandOptions& options, const GlobalOptions& global) {
  OutputPaths paths;
  paths.InputFolder(options.campaign_folder)
      .Input(options.phasor_input.phasors_file)
      .Input(options.result_file)
      .Output("-o", options.output);
  if (!options.curves.empty()) paths.OutputPrefix("--curves", options.curves, {".csv", ".gp", ".png"});
  paths.Check();
  RequireFitWithinModelHarmonics(options.fit_harmonics, options.harmonics);
  // Before the campaign is read; the library's names ([0] is "none").
  const std::vector<std::string> names = solver::CandidateNames();
  for (const auto& name : options.candidates) {
    if (std::find(names.begin() + 1, names.end(), name) != names.end()) continue;
    std::string known;
    for (auto n = names.begin() + 1; n != names.end(); ++n) known += (known.empty() ? "" : ", ") + *n;
    throw std::invalid_argument("--candidates: unknown candidate '" + name + "' (known: " + known + ")");
  }
  const CampaignForAnalysis analysis = ReadCampaignForAnalysis("diagnose", options.campaign_folder, options.fit_channels,
                                                               options.validate_channels, global);
  const signal::Campaign& campaign = analysis.campaign;
  if (!options.result_file.empty()) {
    const solver::ResultFile result = solver::ReadResultFile(options.result_file);
    signal::RequireDerivedFrom(
        {.file = "--result " + options.result_file, .sha256 = result.campaign.sha256, .name = result.campaign.name},
        campaign, "give the result.json that 'beamid identify' wrote for this campaign (or identify it again)");
  }
  const signal::PhasorSet phasors =
      ReadOrExtractPhasors(campaign, options.phasor_input, std::max(5, options.fit_harmonics), global);
  const solver::FitData fit = solver::MakeFitData(
      campaign, phasors, {.channels = analysis.fit_channels, .num_fit_harmonics = options.fit_harmonics});
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
      .campaign_name = campaign.name,
      .campaign_sha256 = campaign.sha256};
  if (!options.result_file.empty()) {
    file.result_file = std::filesystem::absolute(options.result_file).lexically_normal().string();
  }
  solver::WriteDiagnosisFile(options.output, file);
  if (!options.curves.empty()) {
    const std::string csv = options.curves + ".csv", png = options.curves + ".png", gp = options.curves + ".gp";
    WriteTextFile(csv, solver::ResponseCsv(result));
    const std::string script = PlotScript(result);
    WriteTextFile(gp, script);
    DrawCurves(script, png, csv, global);
  }
  if (!global.quiet) {
    fmt::print("diagnosed {} steps in {:.2f} s: {}{}\n", fit.steps.size(), result.seconds,
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
