#include "solver/workflow/predict_campaign.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <numbers>
#include <optional>
#include <vector>

#include "hb/errors.h"
#include "hb/option_checks.h"
#include "hb/version.h"
#include "signal/campaign.h"
#include "signal/campaign_extractor.h"
#include "signal/campaign_identity.h"
#include "solver/estimation/fit_data.h"
#include "solver/estimation/prediction.h"
#include "solver/estimation/prediction_csv.h"
#include "solver/estimation/result_io.h"
#include "solver/workflow/campaign_input.h"
#include "solver/workflow/output_file.h"
#include "solver/workflow/output_paths.h"

namespace beamid::workflow {

void PredictRequest::Validate() const {
  // The check the command line makes as it parses, for a caller without it.
  option_checks::RequireInRange("--x", position_m, 0.0, 100.0);
  OutputPaths paths;
  paths.Input(result_file).InputFolder(campaign_folder).Output("-o", output);
  if (!csv_output.empty()) paths.Output("--csv", csv_output);
  paths.Check();
}

std::string PredictOutcome::Unconverged() const {
  std::string unconverged;
  for (const solver::PredictionStep& p : file.steps)
    if (!p.converged) unconverged += (unconverged.empty() ? "" : ", ") + p.file;
  return unconverged;
}

PredictOutcome PredictCampaign(const PredictRequest& options, const RunObserver& observer) {
  options.Validate();
  const solver::ResultFile result = solver::ReadResultFile(options.result_file);
  const solver::IdentifiedModel model = solver::ToIdentifiedModel(result);
  // The campaign first: one the result was not identified from is refused
  // before any work. Another campaign of the same layout has steps of the
  // same file names: the comparison would be with the wrong recordings.
  std::optional<signal::Campaign> campaign;
  if (!options.campaign_folder.empty()) {
    campaign = ReadCampaignAndWarn("predict", options.campaign_folder, observer);
    signal::RequireDerivedFrom(
        {.file = options.result_file, .sha256 = result.campaign.sha256, .name = result.campaign.name}, *campaign,
        "compare a result with the campaign it was identified from (or identify this campaign again)");
  }
  ObservedTask progress(observer, "predict");
  const std::vector<solver::PredictedStep> steps = solver::PredictAt(model, options.position_m);
  progress.End();
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
  PredictOutcome outcome{.num_steps = steps.size(), .family = model.family, .output = options.output};
  solver::PredictionFile& file = outcome.file;
  file = {.beamid_version = kVersion,
          .result_file = options.result_file,
          .campaign_sha256 = result.campaign.sha256,
          .model_kind = model.family->Kind(),
          .position_m = options.position_m,
          .compared_channel = compared,
          .compared_quantity = compared.empty() ? "" : quantity,
          .steps = {}};
  double& worst = outcome.worst_h1_relative_error;
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
  if (!options.csv_output.empty()) {
    solver::CsvChannelUnit unit;
    if (campaign)
      for (const auto& s : campaign->sensors)
        if (s.channel == compared) unit = {.unit = s.unit, .to_si_factor = s.to_si_factor};
    WriteTextFile(options.csv_output, solver::PredictionCsv(file, unit));
  }
  return outcome;
}

}  // namespace beamid::workflow
