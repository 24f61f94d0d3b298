// beamid identify: the support's parameters from a whole stepped-sine
// campaign (exact harmonic balance or the seed's multiple-scales model,
// Ipopt), with uncertainty, fit quality and the prediction error at held-out
// channels. The work is workflow::IdentifyCampaign; this file parses the
// options, prints the outcome and maps a misfit to exit 5.
#include <optional>

#include <fmt/core.h>

#include "solver/cli/cli_output.h"
#include "solver/cli/command_registry.h"
#include "solver/estimation/damping_laws.h"
#include "solver/estimation/identify.h"
#include "solver/estimation/model_family.h"
#include "solver/estimation/robust_fit.h"
#include "solver/report/held_out_summary.h"
#include "solver/workflow/identify_campaign.h"

namespace beamid::cli {
namespace {

// The steps the robust fit found outlying, and every parameter with and without them.
void PrintRobustFit(const solver::RobustFitResult& robust, const solver::IdentifyResult& ordinary) {
  if (robust.outliers.empty()) return;
  fmt::print("  robust fit: {}\n", robust.note);
  if (!robust.applied) return;
  fmt::print("    {:<10} {:>14} {:>14}   (ordinary fit: reduced chi-square {:.3g}; robust: {:.3g})\n", "parameter",
             "without them", "with them", ordinary.reduced_chi_square, robust.fit.reduced_chi_square);
  for (std::size_t j = 0; j < robust.fit.parameters.size(); ++j)
    fmt::print("    {:<10} {:>14.6g} {:>14.6g} {}\n", robust.fit.parameters[j].name, robust.fit.parameters[j].value,
               ordinary.parameters[j].value, robust.fit.parameters[j].unit);
}

void PrintParameters(const std::vector<solver::ParameterEstimate>& parameters) {
  for (const auto& p : parameters)
    fmt::print("  {:<10} = {:>12.6g} ± {:<10.3g} {}   (95 %: {:.6g} … {:.6g})\n", p.name, p.value, p.std, p.unit,
               p.lower_95, p.upper_95);
}

// The residual model error, on its own, and its share of each interval.
void PrintModelErrors(const solver::IdentifyResult& result) {
  if (result.model_errors.empty()) return;
  std::string harmonics, shares;
  for (std::size_t k = 0; k < result.model_errors.size(); ++k) {
    const solver::ModelErrorEstimate& e = result.model_errors[k];
    harmonics += e.lower_95 > 0.0 ? fmt::format("{}h{} {:.2g} (95 %: {:.2g} … {:.2g})", k ? ", " : "", k + 1,
                                                e.relative, e.lower_95, e.upper_95)
                                  : fmt::format("{}h{} not resolved (95 %: below {:.2g})", k ? ", " : "", k + 1,
                                                e.upper_95);
  }
  for (const auto& p : result.parameters)
    if (p.std > 0.0)
      shares += fmt::format("{}{} {:.0f} %", shares.empty() ? "" : ", ", p.name,
                            100.0 * p.std_model_error * p.std_model_error / (p.std * p.std));
  fmt::print("  residual model error beyond the phasors' stated sigma, relative to each channel's fundamental: {}\n",
             harmonics);
  fmt::print("  the intervals above hold it; its share of each variance: {}\n", shares);
}

void RunIdentify(const workflow::IdentifyRequest& request, const GlobalOptions& global) {
  const workflow::IdentifyOutcome outcome = workflow::IdentifyCampaign(request, CliObserver(global));
  const solver::IdentifyResult& result = outcome.Result();
  if (!global.quiet) {
    const solver::FitData& fit = outcome.fit;
    const solver::DampingLawEnvelope& damping_laws = outcome.damping_laws;
    fmt::print("identified ({}) from {} steps, {} channel(s), harmonics 1..{} in {:.2f} s ({} of {} starts reached the best fit)\n",
               outcome.family->Description(), fit.steps.size(), fit.channels.size(),
               fit.num_fit_harmonics, result.seconds, result.starts_at_best,
               result.starts.size());
    // The answer first: the parameters under the damping law the data accept.
    const solver::DampingLawFit* answer = solver::AnswerLaw(damping_laws);
    const bool law_rejected = answer != nullptr && answer != &damping_laws.laws.front();
    if (law_rejected)
      fmt::print("  the data reject the loss factor the fit assumes; under the {} law, which they accept:\n",
                 answer->law);
    PrintParameters(law_rejected ? answer->parameters : result.parameters);
    if (law_rejected) {
      fmt::print("  under the rejected loss factor (reduced chi-square {:.3g} against {:.3g}):\n",
                 result.reduced_chi_square, answer->reduced_chi_square);
      PrintParameters(result.parameters);
    }
    fmt::print("  reduced chi-square {:.3g} (chi-square {:.4g} over {} degrees of freedom)\n", result.reduced_chi_square,
               result.chi_square, result.degrees_of_freedom);
    PrintModelErrors(result);
    for (const auto& s : outcome.result_file.unsettled_steps)
      fmt::print("  step {} {:.4g} Hz ({}) was recorded before it settled: its uncertainty includes a {:.2f} % change "
                 "between the halves of its analysed part; re-record it with a longer settle\n",
                 s.level, s.frequency_hz, s.file, 100.0 * s.change_relative);
    PrintRobustFit(outcome.robust, outcome.ordinary);
    PrintDampingLaws(damping_laws);
    if (result.minima.minima.size() > 1)
      fmt::print("  the starts reached {} distinct minima; the second is {:.3g} worse in chi-square ({})\n",
                 result.minima.minima.size(), result.minima.second_chi_square_gap,
                 result.minima.decisive ? "ruled out by the data" : "NOT ruled out by the data");
    for (const auto& v : outcome.result_file.validation)
      fmt::print("  held-out {}: {}\n", v.channel, solver::HeldOutSummary(v));
    for (const auto& w : result.warnings) fmt::print("  warning: {}\n", w);
    fmt::print("  verdict: {}\n", result.verdict.text);
    fmt::print("wrote {}{}\n", request.output, request.csv_output.empty() ? "" : " and " + request.csv_output);
  }
  // Exit 5: fitted and written, but the model misses the data beyond their noise.
  if (!outcome.WithinNoise())
    throw ModelMissesData(result.verdict.text + " (the result is in " + request.output + ")");
}

BEAMID_REGISTER_COMMAND("identify", [](CLI::App& app, const GlobalOptions& global) {
  auto request = std::make_shared<workflow::IdentifyRequest>();
  // --fit binds to a list; the request's is unset when none is given.
  auto fit_channels = std::make_shared<std::vector<std::string>>();
  CLI::App* sub = app.add_subcommand(
      "identify",
      "Identify the support (k1, k2, k3, c) from a stepped-sine campaign.\n"
      "Example: beamid identify campaign/ --fit acc1,acc2 --validate acc3 -o result.json");
  sub->add_option("campaign", request->campaign_folder, "Campaign folder (holds campaign.json)")->required();
  sub->add_option("--fit", *fit_channels,
                  "Response channels to fit (default: every sensor neither ignored nor held out)")
      ->delimiter(',');
  sub->add_option("--validate", request->validate_channels, "Held-out channels to predict and compare")
      ->delimiter(',');
  std::string families;
  for (const solver::ModelFamily* family : solver::ModelFamilies())
    families += (families.empty() ? "" : ", ") + family->Name() + " (" + family->Description() + ")";
  sub->add_option("--model", request->model, "Model family: " + families)
      ->check([](const std::string& name) {
        for (const solver::ModelFamily* family : solver::ModelFamilies())
          if (family->Name() == name) return std::string();
        return "unknown model family '" + name + "' (use " + solver::ModelFamilyNames() + ")";
      })
      ->capture_default_str();
  AddPhasorInputOptions(sub, &request->phasor_input);
  AddModelHarmonicsOptions(sub, &request->harmonics, &request->fit_harmonics, "Harmonics of the model (hb; ms has 3)");
  AddPhasorUncertaintyOption(sub, &request->phasor_uncertainty);
  sub->add_option("--starts", request->starts, "Further starts besides the direct estimate")
      ->check(CLI::Range(0, 1000))
      ->capture_default_str();
  sub->add_option("--workers", request->workers, "Worker processes that run the starts in parallel (0: one per core)")
      ->check(CLI::Range(0, 256))
      ->capture_default_str();
  sub->add_flag("--fit-ei-scale", request->fit_ei_scale, "Also fit a scale of the nominal bending stiffness EI");
  sub->add_flag("--fix-loss-factor", request->fix_loss_factor,
                "Do not fit the beam's structural loss factor η; hold it at --beam-loss-factor");
  sub->add_flag("!--no-damping-laws", request->damping_envelope,
                "Do not refit under the other beam damping laws (Rayleigh, mass- and stiffness-proportional): faster, "
                "but no model-form intervals");
  sub->add_flag("!--no-robust", request->robust,
                "Do not test the steps for outliers: fit every step with its full weight, even a faulty one");
  sub->add_option("--beam-loss-factor", request->beam_loss_factor,
                  "The beam's structural loss factor: the start of its fit, or its value with --fix-loss-factor")
      ->check(FiniteRange(0.0, 1.0))
      ->capture_default_str();
  sub->add_option("-o,--output", request->output, "Result file (JSON)")->capture_default_str();
  sub->add_option("--csv", request->csv_output,
                  "Also write the parameters with their 95 % and total intervals as a CSV table");
  sub->callback([request, fit_channels, &global] {
    // No --fit: every sensor neither ignored nor held out.
    request->fit_channels = fit_channels->empty() ? std::nullopt : std::optional(*fit_channels);
    RunIdentify(*request, global);
  });
});

}  // namespace
}  // namespace beamid::cli
