// The diagnose use case: where the base model misses a campaign, which
// left-out physics explains it (every candidate refitted and validated on the
// held-out channels), and the fit with it; the diagnosis file written, and
// the response curves when asked. Everything `beamid diagnose` prints is in
// the outcome; the workflow prints nothing.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "solver/diagnosis/diagnosis.h"
#include "solver/workflow/campaign_input.h"
#include "solver/workflow/run_observer.h"

namespace beamid::workflow {

struct DiagnoseRequest {
  std::string campaign_folder;  // holds campaign.json
  // The response channels to fit; unset: every sensor neither ignored nor
  // held out. A list that is set must name at least one channel.
  std::optional<std::vector<std::string>> fit_channels;
  std::vector<std::string> validate_channels;  // held out: predicted and compared
  std::vector<std::string> candidates;         // physics candidates to try (empty: all)
  PhasorInput phasor_input;
  int harmonics = 5;          // H of the base model (1..50)
  int fit_harmonics = 3;      // harmonics 1..K fitted (1..50, K <= H)
  solver::PhasorUncertainty phasor_uncertainty = solver::PhasorUncertainty::kPropagated;
  int workers = 0;            // parallel refits (0: one per core; up to 256)
  double significance = 0.01;  // family-wise significance of naming a cause (1e-12 .. 0.5)
  bool recording_check = true;  // try the measurement artefacts before the physics
  std::string output = "diagnosis.json";
  std::string curves;       // prefix of PREFIX.csv, .gp and .png ("": none)
  std::string csv_output;   // also the candidate table as CSV ("": none)
  std::string result_file;  // identify's result.json, named in the diagnosis ("": none)

  // Throws InputError naming the field (by its command-line option) and the
  // fix: a value out of range, an empty list of fitted channels, an output
  // that would replace an input (solver/workflow/output_paths.h), K > H, an
  // unknown candidate. The campaign and the result file are checked as they
  // are read.
  void Validate() const;
};

struct DiagnoseOutcome {
  solver::DiagnosisResult diagnosis;
  std::size_t num_steps = 0;  // the fitted steps
  std::string output;
  // With curves: why PREFIX.png was not drawn (gnuplot missing or failing;
  // the CSV and the script are written), empty when it was.
  std::string curves_problem;
};

// Validates the request, reads the campaign (and checks that result_file is
// this campaign's), reads or extracts its phasors, diagnoses, writes
// request.output and the curves. Tasks told to the observer: "extract"
// (unless phasors are given), then "diagnose".
DiagnoseOutcome DiagnoseCampaign(const DiagnoseRequest& request, const RunObserver& observer = {});

}  // namespace beamid::workflow
