#include "solver/workflow/diagnose_campaign.h"

#include <algorithm>
#include <filesystem>

#include "hb/errors.h"
#include "hb/option_checks.h"
#include "signal/campaign.h"
#include "signal/campaign_identity.h"
#include "solver/diagnosis/candidate_physics.h"
#include "solver/diagnosis/diagnosis_candidates_csv.h"
#include "solver/diagnosis/diagnosis_io.h"
#include "solver/estimation/fit_data.h"
#include "solver/estimation/result_io.h"
#include "solver/workflow/diagnosis_curves.h"
#include "solver/workflow/output_file.h"
#include "solver/workflow/output_paths.h"

namespace beamid::workflow {

void DiagnoseRequest::Validate() const {
  using option_checks::RequireInRange;
  // The checks the command line makes as it parses, for a caller without it.
  RequireInRange("-H (harmonics)", harmonics, 1, option_checks::kMaxHarmonics);
  RequireInRange("--fit-harmonics", fit_harmonics, 1, option_checks::kMaxHarmonics);
  RequireInRange("--workers", workers, 0, 256);
  RequireInRange("--significance", significance, 1e-12, 0.5);
  RequireSomeFitChannel(fit_channels);
  OutputPaths paths;
  paths.InputFolder(campaign_folder).Input(phasor_input.phasors_file).Input(result_file).Output("-o", output);
  if (!curves.empty()) paths.OutputPrefix("--curves", curves, {".csv", ".gp", ".png"});
  if (!csv_output.empty()) paths.Output("--csv", csv_output);
  paths.Check();
  RequireFitWithinModelHarmonics(fit_harmonics, harmonics);
  // Before the campaign is read; the library's names ([0] is "none").
  const std::vector<std::string> names = solver::CandidateNames();
  for (const auto& name : candidates) {
    if (std::find(names.begin() + 1, names.end(), name) != names.end()) continue;
    std::string known;
    for (auto n = names.begin() + 1; n != names.end(); ++n) known += (known.empty() ? "" : ", ") + *n;
    throw InputError("--candidates: unknown candidate '" + name + "' (known: " + known + ")");
  }
}

DiagnoseOutcome DiagnoseCampaign(const DiagnoseRequest& request, const RunObserver& observer) {
  request.Validate();
  const CampaignForAnalysis analysis =
      ReadCampaignForAnalysis("diagnose", request.campaign_folder, request.fit_channels.value_or(std::vector<std::string>{}),
                              request.validate_channels, observer);
  const signal::Campaign& campaign = analysis.campaign;
  if (!request.result_file.empty()) {
    const solver::ResultFile result = solver::ReadResultFile(request.result_file);
    signal::RequireDerivedFrom(
        {.file = "--result " + request.result_file, .sha256 = result.campaign.sha256, .name = result.campaign.name},
        campaign, "give the result.json that 'beamid identify' wrote for this campaign (or identify it again)");
  }
  const signal::PhasorSet phasors =
      ReadOrExtractPhasors(campaign, request.phasor_input, std::max(5, request.fit_harmonics), observer);
  const solver::FitData fit = solver::MakeFitData(
      campaign, phasors,
      {.channels = analysis.fit_channels, .num_fit_harmonics = request.fit_harmonics,
       .uncertainty = request.phasor_uncertainty});
  const solver::FitData validation =
      request.validate_channels.empty()
          ? solver::FitData{}
          : solver::MakeFitData(campaign, phasors,
                                {.channels = request.validate_channels, .num_fit_harmonics = request.fit_harmonics,
                                 .uncertainty = request.phasor_uncertainty});
  // The fitted channels examined up to the 5th harmonic (beyond the fitted ones).
  std::vector<std::string> fitted_channels;
  for (const auto& c : fit.channels) fitted_channels.push_back(c.channel);
  const solver::FitData located = solver::MakeFitData(
      campaign, phasors,
      {.channels = fitted_channels, .num_fit_harmonics = std::max(5, request.fit_harmonics),
       .uncertainty = request.phasor_uncertainty});
  solver::DiagnosisOptions diagnosis;
  diagnosis.model_harmonics = request.harmonics;
  diagnosis.candidates = request.candidates;
  diagnosis.num_workers = request.workers;
  diagnosis.significance = request.significance;
  diagnosis.measurement_artefacts = request.recording_check;
  DiagnoseOutcome out{.num_steps = fit.steps.size(), .output = request.output};
  ObservedTask progress(observer, "diagnose");
  out.diagnosis = solver::Diagnose(fit, validation, located, diagnosis,
                                   [&](double fraction, const std::string&) { progress.Update(fraction); });
  progress.End();
  // The folder absolute, so that `beamid report` can tell it from another
  // campaign's wherever it runs.
  solver::DiagnosisFile file{
      .diagnosis = out.diagnosis,
      .campaign_folder = std::filesystem::absolute(request.campaign_folder).lexically_normal().string(),
      .campaign_name = campaign.name,
      .campaign_sha256 = campaign.sha256,
      .phasor_uncertainty = request.phasor_uncertainty};
  if (!request.result_file.empty())
    file.result_file = std::filesystem::absolute(request.result_file).lexically_normal().string();
  solver::WriteDiagnosisFile(request.output, file);
  if (!request.csv_output.empty()) WriteTextFile(request.csv_output, solver::DiagnosisCandidatesCsv(out.diagnosis));
  if (!request.curves.empty()) out.curves_problem = WriteDiagnosisCurves(out.diagnosis, request.curves);
  return out;
}

}  // namespace beamid::workflow
