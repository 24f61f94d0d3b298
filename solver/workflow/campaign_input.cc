#include "solver/workflow/campaign_input.h"

#include <algorithm>
#include <string>

#include <fmt/core.h>

#include "hb/errors.h"
#include "signal/campaign_extractor.h"
#include "signal/campaign_identity.h"
#include "signal/phasor_set_io.h"

namespace beamid::workflow {

void RequireFitWithinModelHarmonics(int fit_harmonics, int harmonics) {
  if (fit_harmonics > harmonics)
    throw InputError("--fit-harmonics " + std::to_string(fit_harmonics) + " exceeds the model's -H " +
                     std::to_string(harmonics) + ": fit at most the harmonics the model holds");
}

void RequireSomeFitChannel(const std::optional<std::vector<std::string>>& fit_channels) {
  if (fit_channels && fit_channels->empty())
    throw InputError("--fit: the channel list is empty. Fix: name at least one response channel of campaign.json, "
                     "or leave the list unset to fit every sensor neither ignored nor held out");
}

signal::Campaign ReadCampaignAndWarn(const std::string& command, const std::filesystem::path& folder,
                                     const RunObserver& observer) {
  signal::Campaign campaign = signal::ReadCampaign(folder);
  for (const auto& warning : campaign.warnings) observer.Warn(command, warning);
  return campaign;
}

CampaignForAnalysis ReadCampaignForAnalysis(const std::string& command, const std::string& folder,
                                            const std::vector<std::string>& fit_channels,
                                            const std::vector<std::string>& validate_channels,
                                            const RunObserver& observer) {
  CampaignForAnalysis out{.campaign = ReadCampaignAndWarn(command, folder, observer), .fit_channels = fit_channels};
  const signal::Campaign& campaign = out.campaign;
  const auto validated = [&](const std::string& channel) {
    return std::find(validate_channels.begin(), validate_channels.end(), channel) != validate_channels.end();
  };
  for (const auto& channel : fit_channels)
    if (validated(channel))
      throw InputError("--validate " + channel + ": the channel is also fitted (--fit), so its held-out error "
                       "would be a fitted residual, not a prediction. Fix: leave " + channel +
                       " out of --fit or out of --validate");
  if (out.fit_channels.empty())
    for (const auto& sensor : campaign.sensors)
      if (campaign.Use(sensor.channel) != signal::ChannelUse::kIgnored && !validated(sensor.channel))
        out.fit_channels.push_back(sensor.channel);
  if (out.fit_channels.empty()) {
    const std::string campaign_json = (campaign.folder / "campaign.json").string();
    throw InputError(campaign_json + ": no sensor is left to fit: every sensor is listed in ignore_channels" +
                     (validate_channels.empty() ? std::string() : " or held out with --validate") +
                     ". Fix: remove a sensor from ignore_channels in " + campaign_json +
                     (validate_channels.empty() ? std::string() : ", or hold out fewer channels"));
  }
  std::vector<std::string> analysed = out.fit_channels;
  analysed.insert(analysed.end(), validate_channels.begin(), validate_channels.end());
  out.campaign.Analyse(analysed);
  return out;
}

void WarnSkippedSteps(const std::string& command, const signal::PhasorSet& phasors, const RunObserver& observer) {
  for (const auto& step : phasors.skipped)
    observer.Warn(command, fmt::format("skipped {} ({} Hz, {}): {}", step.file, step.nominal_frequency_hz, step.level,
                                       step.reason));
}

signal::PhasorSet ReadOrExtractPhasors(const signal::Campaign& campaign, const PhasorInput& input, int num_harmonics,
                                       const RunObserver& observer) {
  if (!input.phasors_file.empty()) {
    signal::PhasorSet phasors = signal::ReadPhasorSetJson(input.phasors_file);
    // The phasors must be this campaign's, every step once (extracted or
    // skipped) and in its order: a file from another campaign or of a
    // subset would be fitted silently.
    bool same = phasors.steps.size() + phasors.skipped.size() == campaign.steps.size();
    std::size_t extracted = 0, skipped = 0;
    for (std::size_t i = 0; same && i < campaign.steps.size(); ++i) {
      const auto& step = campaign.steps[i];
      if (extracted < phasors.steps.size() && phasors.steps[extracted].file == step.file &&
          phasors.steps[extracted].level == step.level)
        ++extracted;
      else if (skipped < phasors.skipped.size() && phasors.skipped[skipped].file == step.file &&
               phasors.skipped[skipped].level == step.level)
        ++skipped;
      else
        same = false;
    }
    if (!same)
      throw InputError(input.phasors_file + ": these phasors are not the campaign's (" +
                       std::to_string(phasors.steps.size() + phasors.skipped.size()) + " steps against the campaign's " +
                       std::to_string(campaign.steps.size()) +
                       ", or other files or levels). Fix: extract this campaign again (beamid extract) or give "
                       "the phasor file extracted from it");
    // The same files and levels may hold other recordings (another beam,
    // another day): only the content hash tells.
    signal::RequireDerivedFrom({.file = "--phasors " + input.phasors_file,
                                .sha256 = phasors.campaign_sha256,
                                .name = phasors.campaign},
                               campaign,
                               "extract this campaign again (beamid extract " + campaign.folder.string() +
                                   ") or give the phasor file extracted from it");
    if (!phasors.skipped.empty() && !input.skip_bad_steps)
      throw InputError(input.phasors_file + ": " + std::to_string(phasors.skipped.size()) +
                       " steps were skipped at extraction (bad recordings). Fix: add --skip-bad-steps to analyse "
                       "the other steps, or repair the recordings and extract again");
    WarnSkippedSteps("extract", phasors, observer);
    return phasors;
  }
  ObservedTask progress(observer, "extract");
  signal::ExtractOptions extract;
  extract.estimator.num_harmonics = num_harmonics;
  extract.skip_bad_steps = input.skip_bad_steps;
  extract.progress = [&](std::size_t done, std::size_t total, const signal::StepPhasors&) {
    progress.Update(static_cast<double>(done) / total);
  };
  signal::PhasorSet phasors = signal::ExtractCampaign(campaign, extract);
  progress.End();
  WarnSkippedSteps("extract", phasors, observer);
  return phasors;
}

}  // namespace beamid::workflow
