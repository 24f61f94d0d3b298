// beamid predict: the identified model's steady state at any position of the
// beam, for every step of the fit, with uncertainty bands; compared with a
// campaign's sensor there when one is given. The model is the one identify
// used (result.json's model.kind): parameters fitted with multiple scales are
// predicted with multiple scales, not mixed with harmonic balance. The work
// is workflow::PredictCampaign; this prints its outcome and maps a step that
// did not converge to exit 3 (after writing the prediction).
#include <string>

#include <fmt/core.h>

#include "hb/errors.h"
#include "solver/cli/cli_output.h"
#include "solver/cli/command_registry.h"
#include "solver/workflow/predict_campaign.h"

namespace beamid::cli {
namespace {

void RunPredict(const workflow::PredictRequest& request, const GlobalOptions& global) {
  const workflow::PredictOutcome outcome = workflow::PredictCampaign(request, CliObserver(global));
  const std::string& compared = outcome.file.compared_channel;
  if (!global.quiet) {
    fmt::print("predicted {} steps at x = {:.3f} m with the {} model\n", outcome.num_steps, request.position_m,
               outcome.family->Description());
    if (!compared.empty())
      fmt::print("  against {}: worst first-harmonic error {:.2f} %\n", compared, 100 * outcome.worst_h1_relative_error);
    fmt::print("wrote {}{}\n", request.output, request.csv_output.empty() ? "" : " and " + request.csv_output);
  }
  // Exit 3, the prediction written all the same.
  const std::string unconverged = outcome.Unconverged();
  if (!unconverged.empty())
    throw NumericalError("the harmonic balance did not converge at " + unconverged + " (written to " +
                             request.output + " all the same)");
}

BEAMID_REGISTER_COMMAND("predict", [](CLI::App& app, const GlobalOptions& global) {
  auto request = std::make_shared<workflow::PredictRequest>();
  CLI::App* sub = app.add_subcommand(
      "predict",
      "Predict the steady state at any position from an identified model, with uncertainty bands.\n"
      "Example: beamid predict result.json --campaign campaign/ --x 0.45 -o pred.json");
  sub->add_option("result", request->result_file, "result.json of 'beamid identify'")->required();
  sub->add_option("--x", request->position_m, "Position on the beam [m]")
      ->required()
      ->check(FiniteRange(0.0, 100.0));
  sub->add_option("--campaign", request->campaign_folder, "Campaign to compare with (a sensor at x)")
      ->check(NonEmptyPath());
  sub->add_option("-o,--output", request->output, "Output file (JSON)")->capture_default_str();
  sub->add_option("--csv", request->csv_output,
                  "Also write the prediction as CSV for a spreadsheet: per step and harmonic, amplitude and phase; "
                  "the compared sensor's in the unit of its recordings (docs/result-format.md)")
      ->check(NonEmptyPath());
  sub->callback([request, &global] { RunPredict(*request, global); });
});

}  // namespace
}  // namespace beamid::cli
