// The extract use case: the harmonic phasors of every step of a stepped-sine
// campaign (signal/campaign_extractor.h), written as phasors.json (read by
// the fit) and optionally as a CSV table. Everything `beamid extract` prints
// is in the outcome (each step's quality, its warnings among them).
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "signal/phasor_set.h"
#include "solver/workflow/run_observer.h"

namespace beamid::workflow {

struct ExtractRequest {
  std::string campaign_folder;  // holds campaign.json
  int harmonics = 5;            // per channel (1 .. 50)
  std::string output = "phasors.json";
  std::string csv_output;             // also a CSV table ("": none)
  int threads = 0;                    // worker threads (0: one per core; up to 256)
  std::vector<std::string> channels;  // the sensors analysed; empty: every one not ignored
  bool skip_bad_steps = false;        // leave out (and list) the steps whose recordings hold errors
  bool remove_ringing = false;        // fit the frequency step's ringing out of the phasors (signal/settling_transient.h)

  // Throws InputError naming the field (by its command-line option) and the
  // fix: a value out of range, an output that would replace an input
  // (solver/workflow/output_paths.h). The campaign is checked as it is read.
  void Validate() const;
};

struct ExtractOutcome {
  signal::PhasorSet phasors;    // as written
  std::size_t num_sensors = 0;  // of the campaign
  std::string output, csv_output;
};

// Validates the request, reads the campaign, extracts (the task "extract";
// the steps left out are told as warnings), writes the files and returns the
// phasors.
ExtractOutcome ExtractCampaign(const ExtractRequest& request, const RunObserver& observer = {});

}  // namespace beamid::workflow
