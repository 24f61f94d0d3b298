// beamid predict: the identified model's steady state at any position of the
// beam, for every step of the fit, with uncertainty bands; compared with a
// campaign's sensor there when one is given. The model is the one identify
// used (result.json's model.kind): parameters fitted with multiple scales are
// predicted with multiple scales, not mixed with harmonic balance.
#include <cmath>
#include <numbers>

#include <fmt/core.h>

#include "hb/version.h"
#include "hb/errors.h"
#include "signal/campaign.h"
#include "signal/campaign_extractor.h"
#include "solver/cli/cli_output.h"
#include "solver/cli/command_registry.h"
#include "solver/estimation/fit_data.h"
#include "solver/estimation/prediction.h"

namespace beamid::cli {
namespace {

struct PredictOptions {
  std::string result_file;
  std::string campaign_folder;
  double position_m = 0.0;
  std::string output = "prediction.json";
};

void RunPredict(const PredictOptions& options, const GlobalOptions& global) {
  RequireWritableOutput(options.output, {options.result_file});
  const solver::IdentifiedModel model = solver::ReadIdentifiedModel(options.result_file);
  Progress progress("predict", global);
  const std::vector<solver::PredictedStep> steps = solver::PredictAt(model, options.position_m);
  progress.Done();
  // A campaign sensor within 1 mm of x is compared with the prediction.
  std::string compared;
  int compared_order = 2;  // the compared channel's quantity: 0 displacement, 1 velocity, 2 acceleration
  std::vector<Eigen::VectorXcd> measured;
  if (!options.campaign_folder.empty()) {
    const signal::Campaign campaign = signal::ReadCampaign(options.campaign_folder);
    for (const auto& s : campaign.sensors)
      if (std::abs(s.position_m - options.position_m) < 1e-3) compared = s.channel;
    if (!compared.empty()) {
      const signal::PhasorSet phasors = signal::ExtractCampaign(campaign);
      const solver::FitData data = solver::MakeFitData(campaign, phasors, {.channels = {compared}});
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
  nlohmann::json out_steps = nlohmann::json::array();
  double worst = 0.0;
  for (std::size_t i = 0; i < steps.size(); ++i) {
    const solver::PredictedStep& p = steps[i];
    const double omega = 2 * std::numbers::pi * p.frequency_hz;
    nlohmann::json harmonics = nlohmann::json::array();
    for (Eigen::Index k = 1; k < p.displacement_m.size(); ++k) {
      const std::complex<double> acc = -std::pow(k * omega, 2) * p.displacement_m[k];
      nlohmann::json h = {{"k", k},
                          {"displacement_m", {p.displacement_m[k].real(), p.displacement_m[k].imag()}},
                          {"displacement_std_m", {p.std_real_m[k], p.std_imag_m[k]}},
                          {"acceleration_m_s2", {acc.real(), acc.imag()}},
                          {"acceleration_amplitude_m_s2", std::abs(acc)}};
      if (!measured.empty() && measured[i].size() >= k) {
        // In the compared channel's own quantity (a velocity channel is
        // compared with the predicted velocity, not the acceleration).
        const auto m = measured[i][k - 1];
        const std::complex<double> predicted = solver::DerivativeFactor(compared_order, k * omega) * p.displacement_m[k];
        h[std::string("measured_") + quantity] = {m.real(), m.imag()};
        h[std::string("predicted_") + quantity] = {predicted.real(), predicted.imag()};
        h["relative_error"] = std::abs(predicted - m) / std::max(std::abs(m), 1e-300);
        if (k == 1) worst = std::max(worst, h["relative_error"].get<double>());
      }
      harmonics.push_back(h);
    }
    out_steps.push_back({{"level", p.level},
                         {"file", p.file},
                         {"frequency_Hz", p.frequency_hz},
                         {"converged", p.converged},
                         {"harmonics", harmonics},
                         {"time_s", std::vector<double>(p.time_s.data(), p.time_s.data() + p.time_s.size())},
                         {"acceleration_m_s2", std::vector<double>(p.acceleration_m_s2.data(),
                                                                   p.acceleration_m_s2.data() + p.acceleration_m_s2.size())},
                         {"acceleration_std_m_s2",
                          std::vector<double>(p.acceleration_std_m_s2.data(),
                                              p.acceleration_std_m_s2.data() + p.acceleration_std_m_s2.size())}});
  }
  const nlohmann::json out = {{"command", "predict"},
                              {"beamid_version", kVersion},
                              {"result", options.result_file},
                              {"model", model.kind},
                              {"position_m", options.position_m},
                              {"compared_channel", compared},
                              {"steps", out_steps}};
  WriteTextFile(options.output, out.dump(1));
  if (!global.quiet) {
    fmt::print("predicted {} steps at x = {:.3f} m with the {} model\n", steps.size(), options.position_m,
               model.kind == "ms" ? "multiple-scales" : "harmonic-balance");
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
  sub->add_option("--x", options->position_m, "Position on the beam [m]")->required();
  sub->add_option("--campaign", options->campaign_folder, "Campaign to compare with (a sensor at x)");
  sub->add_option("-o,--output", options->output, "Output file (JSON)")->capture_default_str();
  sub->callback([options, &global] { RunPredict(*options, global); });
});

}  // namespace
}  // namespace beamid::cli
