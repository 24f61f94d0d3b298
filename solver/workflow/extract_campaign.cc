#include "solver/workflow/extract_campaign.h"

#include <stdexcept>

#include "hb/option_checks.h"
#include "signal/campaign.h"
#include "signal/campaign_extractor.h"
#include "signal/phasor_set_io.h"
#include "solver/workflow/campaign_input.h"
#include "solver/workflow/output_file.h"
#include "solver/workflow/output_paths.h"

namespace beamid::workflow {

void ExtractRequest::Validate() const {
  // The check the command line makes as it parses, for a caller without it.
  option_checks::RequireInRange("--threads", threads, 0, 256);
  OutputPaths paths;
  paths.InputFolder(campaign_folder).Output("-o", output);
  if (!csv_output.empty()) paths.Output("--csv", csv_output);
  paths.Check();
  if (harmonics < 1 || harmonics > option_checks::kMaxHarmonics)
    throw InputError("-H/--harmonics must lie between 1 and 50 (got " + std::to_string(harmonics) + ")");
}

ExtractOutcome ExtractCampaign(const ExtractRequest& request, const RunObserver& observer) {
  request.Validate();
  signal::Campaign campaign = ReadCampaignAndWarn("extract", request.campaign_folder, observer);
  campaign.Analyse(request.channels);
  signal::ExtractOptions extract;
  extract.skip_bad_steps = request.skip_bad_steps;
  extract.estimator.settling_transient = request.remove_ringing;
  extract.estimator.num_harmonics = request.harmonics;
  extract.num_threads = request.threads;
  ObservedTask progress(observer, "extract");
  extract.progress = [&](std::size_t done, std::size_t total, const signal::StepPhasors&) {
    progress.Update(static_cast<double>(done) / static_cast<double>(total));
  };
  ExtractOutcome out{.phasors = signal::ExtractCampaign(campaign, extract),
                     .num_sensors = campaign.sensors.size(),
                     .output = request.output,
                     .csv_output = request.csv_output};
  progress.End();
  WarnSkippedSteps("extract", out.phasors, observer);
  WriteTextFile(request.output, signal::PhasorSetToJson(out.phasors));
  if (!request.csv_output.empty()) WriteTextFile(request.csv_output, signal::PhasorSetToCsv(out.phasors));
  return out;
}

}  // namespace beamid::workflow
