// The phasors of a whole campaign: every step's recording is read, validated
// (signal/recording.h) and reduced to phasors (signal/phasor_estimator.h).
// Steps are independent, so they run on worker threads; the result keeps the
// campaign's step order. Every step is tried: the problems of all failing
// steps are reported together, in one InputError listing each step's file
// and errors (in campaign order) — or, with skip_bad_steps, those steps are
// left out of the result and listed in PhasorSet::skipped with their errors.
// A recording's warnings and notes (problems of channels the analysis does
// not use, Campaign::Use) go to the step's quality.
#pragma once

#include <cstddef>
#include <functional>

#include "signal/campaign.h"
#include "signal/phasor_estimator.h"
#include "signal/phasor_set.h"
#include "signal/recording_validator.h"

namespace beamid::signal {

struct ExtractOptions {
  PhasorEstimatorOptions estimator;
  RecordingChecks checks;
  int num_threads = 0;  // 0: one per hardware core
  // Leave out the steps whose recordings hold errors instead of stopping.
  bool skip_bad_steps = false;
  // Called (serialised) after each step with the number of steps done.
  std::function<void(std::size_t done, std::size_t total, const StepPhasors& step)> progress;

  // Throws InputError naming the field, its value and the allowed range.
  void Validate() const;
};

PhasorSet ExtractCampaign(const Campaign& campaign, const ExtractOptions& options = {});

}  // namespace beamid::signal
