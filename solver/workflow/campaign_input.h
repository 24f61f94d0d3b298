// What a model-based workflow reads of a campaign: campaign.json of a folder
// (its warnings told to the observer), the channels a fit uses, and the
// phasors, read from `beamid extract`'s file or extracted.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "signal/campaign.h"
#include "signal/phasor_set.h"
#include "solver/workflow/run_observer.h"

namespace beamid::workflow {

// The check, before any work, that the model holds every fitted harmonic
// (K <= H); throws InputError naming --fit-harmonics and -H.
void RequireFitWithinModelHarmonics(int fit_harmonics, int harmonics);

// An explicit list of fitted channels (as opposed to none: every sensor
// neither ignored nor held out) names at least one; throws InputError naming
// --fit otherwise.
void RequireSomeFitChannel(const std::optional<std::vector<std::string>>& fit_channels);

// campaign.json of a folder, its warnings told to the observer as warnings
// of `command` (a recording that is a byte copy of another step's,
// signal::Campaign::warnings).
signal::Campaign ReadCampaignAndWarn(const std::string& command, const std::filesystem::path& folder,
                                     const RunObserver& observer);

// campaign.json of a folder and the channels a fit uses: fit_channels as
// given, or (none given) every sensor neither ignored nor held out; the fitted
// and held-out sensors are marked as analysed, so that only their recordings'
// problems stop the run (signal::Campaign::Use). Throws InputError for a
// channel both fitted and held out (its "prediction" would be a fit) and for a
// fit with no channel left.
struct CampaignForAnalysis {
  signal::Campaign campaign;
  std::vector<std::string> fit_channels;
};
CampaignForAnalysis ReadCampaignForAnalysis(const std::string& command, const std::string& folder,
                                            const std::vector<std::string>& fit_channels,
                                            const std::vector<std::string>& validate_channels,
                                            const RunObserver& observer);

// Where a model-based workflow takes its phasors from.
struct PhasorInput {
  std::string phasors_file;     // --phasors: the output of `beamid extract`; empty: extract
  bool skip_bad_steps = false;  // --skip-bad-steps: analyse the steps whose recordings hold no error
};

// The phasors of a campaign: read from input.phasors_file when given (and
// checked to be this campaign's: its steps, and its campaign_sha256 against
// the campaign's content hash, signal/campaign_identity.h), else extracted
// with harmonics 1..num_harmonics as the task "extract". The steps left out
// (skipped) are told to the observer, one warning each.
signal::PhasorSet ReadOrExtractPhasors(const signal::Campaign& campaign, const PhasorInput& input, int num_harmonics,
                                       const RunObserver& observer);

// The steps an extraction left out, one warning of `command` each.
void WarnSkippedSteps(const std::string& command, const signal::PhasorSet& phasors, const RunObserver& observer);

}  // namespace beamid::workflow
