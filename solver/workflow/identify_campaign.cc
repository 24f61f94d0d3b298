#include "solver/workflow/identify_campaign.h"

#include <algorithm>
#include <filesystem>
#include <memory>

#include "hb/errors.h"
#include "hb/option_checks.h"
#include "signal/campaign.h"
#include "solver/estimation/result_io.h"
#include "solver/estimation/result_parameters_csv.h"
#include "solver/workflow/output_file.h"
#include "solver/workflow/output_paths.h"

namespace beamid::workflow {
const solver::ModelFamily& IdentifyRequest::Validate() const {
  using option_checks::RequireInRange;
  // The checks the command line makes as it parses, for a caller without it.
  RequireInRange("-H (harmonics)", harmonics, 1, option_checks::kMaxHarmonics);
  RequireInRange("--fit-harmonics", fit_harmonics, 1, option_checks::kMaxHarmonics);
  RequireInRange("--starts", starts, 0, 1000);
  RequireInRange("--workers", workers, 0, 256);
  RequireInRange("--beam-loss-factor", beam_loss_factor, 0.0, 1.0);
  RequireSomeFitChannel(fit_channels);
  OutputPaths paths;
  paths.InputFolder(campaign_folder).Input(phasor_input.phasors_file).Output("-o", output);
  if (!csv_output.empty()) paths.Output("--csv", csv_output);
  paths.Check();
  const solver::ModelFamily& family = solver::FindModelFamily(model);
  RequireFitWithinModelHarmonics(fit_harmonics, harmonics);
  return family;
}

IdentifyOutcome IdentifyCampaign(const IdentifyRequest& request, const RunObserver& observer) {
  const solver::ModelFamily& family = request.Validate();
  const CampaignForAnalysis analysis =
      ReadCampaignForAnalysis("identify", request.campaign_folder, request.fit_channels.value_or(std::vector<std::string>{}),
                              request.validate_channels, observer);
  const signal::Campaign& campaign = analysis.campaign;
  const signal::PhasorSet phasors =
      ReadOrExtractPhasors(campaign, request.phasor_input, std::max(5, request.fit_harmonics), observer);
  IdentifyOutcome out{.family = &family, .output = request.output};
  out.fit = solver::MakeFitData(campaign, phasors,
                                {.channels = analysis.fit_channels, .num_fit_harmonics = request.fit_harmonics,
                                 .uncertainty = request.phasor_uncertainty});
  const solver::FitData& fit = out.fit;
  const solver::FitData validation =
      request.validate_channels.empty()
          ? solver::FitData{}
          : solver::MakeFitData(campaign, phasors,
                                {.channels = request.validate_channels, .num_fit_harmonics = request.fit_harmonics,
                                 .uncertainty = request.phasor_uncertainty});
  solver::ModelStructure structure = solver::PolynomialModel({.k1_Nm_rad = 100.0});
  if (request.fit_ei_scale) structure.linear.push_back(solver::BendingStiffnessScale());
  // The beam's own damping is unknown in a real test and, left out, ends up
  // in c with an interval that does not cover the truth: fit it by default.
  if (!request.fix_loss_factor)
    structure.linear.push_back(solver::LossFactor(std::max(request.beam_loss_factor, 1e-4)));
  solver::IdentifyOptions identify;
  identify.family = &family;
  identify.model.num_harmonics = request.harmonics;
  identify.model.beam_loss_factor = request.beam_loss_factor;
  identify.num_starts = request.starts;
  identify.num_workers = request.workers;
  ObservedTask progress(observer, "identify");
  const auto report_progress = [&](double fraction, const std::string& what) { progress.Update(0.9 * fraction, what); };
  out.ordinary = solver::Identify(fit, structure, identify, report_progress);
  const solver::IdentifyResult& ordinary = out.ordinary;
  // A faulty step (a record cut before it settled, a glitch) must not pull
  // the parameters by its whole chi-square: the outlier test leaves out a few
  // such steps, never a misfit spread over many (solver/estimation/robust_fit.h).
  out.robust = solver::RobustFitResult{.data = fit, .fit = ordinary};
  if (request.robust) {
    progress.Update(0.92, "testing the steps for outliers");
    out.robust = solver::RobustRefit(fit, structure, ordinary, identify);
  }
  const solver::RobustFitResult& robust = out.robust;
  const solver::IdentifyResult& result = robust.fit;
  // The beam's damping law is assumed, never known: the other laws' refits
  // give the parameters' model-form intervals (solver/estimation/damping_laws.h).
  // Only for a fit within the noise: the parameters of a model that misses
  // the data are not to be quoted with any interval (diagnose first), and
  // refits of it under other laws ran for minutes.
  if (request.damping_envelope && family.Kind() == solver::ModelKind::kHarmonicBalance &&
      result.verdict.within_noise) {
    progress.Update(0.95, "refitting under the other beam damping laws");
    out.damping_laws = solver::FitDampingLaws(robust.data, structure, result, identify);
  }
  progress.End();

  const std::unique_ptr<solver::FitProblem> problem = family.MakeProblem(robust.data, structure, identify.model);
  problem->FeasiblePoint(result.starts[result.best_start].scaled_at);  // the winning run's scales
  solver::FitData fit_with_loss = robust.data;
  fit_with_loss.beam.loss_factor = request.beam_loss_factor;
  solver::ResultFile& result_file = out.result_file;
  result_file = solver::MakeResultFile(
      fit_with_loss, solver::WithoutLeftOutSteps(validation, robust), *problem, result,
      {.campaign_folder = request.campaign_folder,
       .campaign_name = campaign.name,
       // `beamid report` finds the campaign from anywhere on this machine.
       .campaign_absolute_folder = std::filesystem::absolute(request.campaign_folder).lexically_normal().string(),
       .campaign_sha256 = campaign.sha256,
       .family = &family});
  result_file.damping_laws = out.damping_laws;
  if (!robust.outliers.empty())
    result_file.robust_fit = solver::ResultRobustFit{.applied = robust.applied,
                                                     .note = robust.note,
                                                     .outliers = robust.outliers,
                                                     .ordinary_parameters = ordinary.parameters,
                                                     .ordinary_chi_square = ordinary.chi_square,
                                                     .ordinary_degrees_of_freedom = ordinary.degrees_of_freedom};
  for (const auto& s : fit.steps)
    if (s.unsettled)
      result_file.unsettled_steps.push_back({.level = s.level,
                                             .file = s.file,
                                             .frequency_hz = s.FrequencyHz(),
                                             .change_relative = s.unsettled_change_relative});
  solver::WriteResultFile(request.output, result_file);
  if (!request.csv_output.empty()) WriteTextFile(request.csv_output, solver::ResultParametersCsv(result_file));
  return out;
}

}  // namespace beamid::workflow
