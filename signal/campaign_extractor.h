// The phasors of a whole campaign: every step's recording is read, validated
// (signal/recording.h) and reduced to phasors (signal/phasor_estimator.h).
// Steps are independent, so they run on worker threads; the result keeps the
// campaign's step order. The first failing step (in campaign order) stops the
// extraction and its error is rethrown: InputError for bad input, and
// std::runtime_error, prefixed with the file, for a numerical failure.
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
  // Called (serialised) after each step with the number of steps done.
  std::function<void(std::size_t done, std::size_t total, const StepPhasors& step)> progress;

  // Throws InputError naming the field, its value and the allowed range.
  void Validate() const;
};

PhasorSet ExtractCampaign(const Campaign& campaign, const ExtractOptions& options = {});

}  // namespace beamid::signal
