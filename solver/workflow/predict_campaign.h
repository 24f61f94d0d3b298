// The predict use case: an identified model's steady state at any position
// of the beam, for every step of its fit, with uncertainty bands; compared
// with a campaign's sensor there (within 1 mm) when a campaign is given. The
// model is the one identify used (result.json's model.kind). The prediction
// file is written also when a step did not converge: that is an outcome
// (Unconverged() not empty), not an error. Everything `beamid predict`
// prints is in the outcome.
#pragma once

#include <cstddef>
#include <string>

#include "solver/estimation/model_family.h"
#include "solver/estimation/prediction_io.h"
#include "solver/workflow/run_observer.h"

namespace beamid::workflow {

struct PredictRequest {
  std::string result_file;      // result.json of identify
  std::string campaign_folder;  // the campaign to compare with ("": none); the one the result is of
  double position_m = 0.0;      // on the beam (0 .. 100)
  std::string output = "prediction.json";
  std::string csv_output;  // also the prediction as CSV, compared in the sensor's own unit ("": none)

  // Throws InputError naming the field (by its command-line option) and the
  // fix: a position out of range, an output that would replace an input
  // (solver/workflow/output_paths.h). The result and the campaign are
  // checked as they are read.
  void Validate() const;
};

struct PredictOutcome {
  solver::PredictionFile file;  // as written
  std::size_t num_steps = 0;
  const solver::ModelFamily* family = nullptr;  // the result's
  double worst_h1_relative_error = 0.0;         // against file.compared_channel (none: 0)
  std::string output;

  // The files of the steps whose balance did not converge, comma-separated ("": all did).
  std::string Unconverged() const;
};

// Validates the request, reads the result (and the campaign, refused when the
// result is not of it), predicts (the task "predict"), compares, writes
// request.output and returns it.
PredictOutcome PredictCampaign(const PredictRequest& request, const RunObserver& observer = {});

}  // namespace beamid::workflow
