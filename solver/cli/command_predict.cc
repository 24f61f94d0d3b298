// beamid predict: the identified model's steady state at any position of the
// beam, for every step of the fit, with uncertainty bands; compared with a
// campaign's sensor there when one is given. The model is the one identify
// used (result.json's model.kind): parameters fitted with multiple scales are
// predicted with multiple scales, not mixed with harmonic balance.
#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>

#include <fmt/core.h>

#include "hb/errors.h"
#include "hb/version.h"
#include "signal/campaign.h"
#include "signal/campaign_extractor.h"
#include "signal/campaign_identity.h"
#include "solver/cli/cli_output.h"
#include "solver/cli/command_registry.h"
#include "solver/workflow/output_paths.h"
#include "solver/estimation/fit_data.h"
#include "solver/estimation/prediction.h"
#include "solver/estimation/prediction_io.h"
#include "solver/estimation/result_io.h"

namespace beamid::cli {
namespace {

struct PredictOptions {
  std::string result_file;
  std::string campaign_folder;
  double position_m = 0.0;
  std::string output = "prediction.json";
};

void RunPredict(const PredictOptions& options, const GlobalOptions& global) {
  workflow::OutputPaths()
      .Input(options.result_file)
      .InputFolder(options.campaign_folder)
      .Output("-o", options.output)
      .Check();
  const solver::ResultFile result = solver::ReadResultFile(options.result_file);
  const solver::IdentifiedModel model = solver::ToIdentifiedModel(result);
  // The campaign first: one the result was not identified from is refused
  // before any work. Another campaign of the same layout has steps of the
  // same file names: the comparison would be with the wrong recordings.
  std::optional<signal::Campaign> campaign;
  if (!options.campaign_folder.empty()) {
    campaign = ReadCampaignAndWarn("predict", options.campaign_folder, global);
    signal::RequireDerivedFrom(
        {.file = options.result_file, .sha256 = result.campaign.sha256, .name = result.campaign.name}, *campaign,
        "compare a result with the campaign it was identified from (or identify this campaign again)");
  }
  Progress progress("predict", global);
  const std::vector<solver::PredictedStep> steps = solver::PredictAt(model, options.position_m);
  progress.Done();
  // A campaign sensor within 1 mm of x is compared with the prediction.
  std::string compared;
  int compared_order = 2;  // the compared channel's quantity: 0 displacement, 1 velocity, 2 acceleration
  std::vector<Eigen::VectorXcd> measured;
  if (campaign) {
    for (const auto& s : campaign->sensors)
      if (std::abs(s.position_m - options.position_m) < 1e-3) compared = s.channel;
    if (!compared.empty()) {
      const signal::PhasorSet phasors = signal::ExtractCampaign(*campaign);
      const solver::FitData data = solver::MakeFitData(*campaign, phasors, {.channels = {compared}});
      compared_order = data.channels.front().derivative_order;
      int matched = 0;
      for (const solver::PredictedStep& p : steps) {
        Eigen::VectorXcd m;
        for (const auto& s : data.steps)
          if (s.file == p.file) m = s.measured.row(0).transpose();
        matched += m.size() > 0;
        measured.push_back(m);
      }
      // A result from another campaign matches none of its steps: a "worst
      // error" over no step would read 0 %.
      if (matched == 0)
        throw InputError(options.result_file + ": none of its steps is a step of the campaign " +
                         options.campaign_folder +
                         ". Fix: compare a result with the campaign it was identified from");
    }
  }
  const char* const quantity = compared_order == 0 ? "displacement_m" : compared_order == 1 ? "velocity_m_s" : "acceleration_m_s2";
  solver::PredictionFile file{.beamid_version = kVersion,
                              .result_file = options.result_file,
                              .campaign_sha256 = result.campaign.sha256,
                              .model_kind = model.family->Kind(),
                              .position_m = options.position_m,
                              .compared_channel = compared,
                              .compared_quantity = compared.empty() ? "" : quantity,
                              .steps = {}};
  double worst = 0.0;
  for (std::size_t i = 0; i < steps.size(); ++i) {
    const solver::PredictedStep& p = steps[i];
    const double omega = 2 * std::numbers::pi * p.frequency_hz;
    solver::PredictionStep& out = file.steps.emplace_back();
    out.level = p.level;
    out.file = p.file;
    out.frequency_hz = p.frequency_hz;
    out.converged = p.converged;
    for (Eigen::Index k = 1; k < p.displacement_m.size(); ++k) {
      const std::complex<double> acc = -std::pow(k * omega, 2) * p.displacement_m[k];
      solver::PredictionHarmonic& h = out.harmonics.emplace_back();
      h.k = static_cast<int>(k);
      h.displacement_m = p.displacement_m[k];
      h.displacement_std_real_m = p.std_real_m[k];
      h.displacement_std_imag_m = p.std_imag_m[k];
      h.acceleration_m_s2 = acc;
      h.acceleration_amplitude_m_s2 = std::abs(acc);
      if (!measured.empty() && measured[i].size() >= k) {
        // In the compared channel's own quantity (a velocity channel is
        // compared with the predicted velocity, not the acceleration).
        h.compared = true;
        h.measured = measured[i][k - 1];
        h.predicted = solver::DerivativeFactor(compared_order, k * omega) * p.displacement_m[k];
        h.relative_error = std::abs(h.predicted - h.measured) / std::max(std::abs(h.measured), 1e-300);
        if (k == 1) worst = std::max(worst, h.relative_error);
      }
    }
    out.time_s.assign(p.time_s.data(), p.time_s.data() + p.time_s.size());
    out.acceleration_m_s2.assign(p.acceleration_m_s2.data(), p.acceleration_m_s2.data() + p.acceleration_m_s2.size());
    out.acceleration_std_m_s2.assign(p.acceleration_std_m_s2.data(),
                                     p.acceleration_std_m_s2.data() + p.acceleration_std_m_s2.size());
  }
  solver::WritePredictionFile(options.output, file);
  if (!global.quiet) {
    fmt::print("predicted {} steps at x = {:.3f} m with the {} model\n", steps.size(), options.position_m,
               model.family->Description());
    if (!compared.empty()) fmt::print("  against {}: worst first-harmonic error {:.2f} %\n", compared, 100 * worst);
    fmt::print("wrote {}\n", options.output);
  }
  std::string unconverged;
  for (const solver::PredictedStep& p : steps)
    if (!p.converged) unconverged += (unconverged.empty() ? "" : ", ") + p.file;
  if (!unconverged.empty())
    throw NumericalError("the harmonic balance did not converge at " + unconverged + " (written to " +
                             options.output + " all the same)");
}

BEAMID_REGISTER_COMMAND("predict", [](CLI::App& app, const GlobalOptions& global) {
  auto options = std::make_shared<PredictOptions>();
  CLI::App* sub = app.add_subcommand(
      "predict",
      "Predict the steady state at any position from an identified model, with uncertainty bands.\n"
      "Example: beamid predict result.json --campaign campaign/ --x 0.45 -o pred.json");
  sub->add_option("result", options->result_file, "result.json of 'beamid identify'")->required();
  sub->add_option("--x", options->position_m, "Position on the beam [m]")
      ->required()
      ->check(FiniteRange(0.0, 100.0));
  sub->add_option("--campaign", options->campaign_folder, "Campaign to compare with (a sensor at x)")
      ->check(NonEmptyPath());
  sub->add_option("-o,--output", options->output, "Output file (JSON)")->capture_default_str();
  sub->callback([options, &global] { RunPredict(*options, global); });
});

}  // namespace
}  // namespace beamid::cli
