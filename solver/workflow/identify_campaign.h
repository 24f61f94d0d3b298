// The identify use case: a stepped-sine campaign in, the support's parameters
// out (exact harmonic balance or the seed's multiple-scales model, Ipopt),
// with the robust refit without outlying steps, the envelope over the beam's
// damping laws, the prediction at held-out channels, and the result file
// written. Everything `beamid identify` prints is in the outcome; the
// workflow prints nothing and decides no exit code: a fit that misses the
// data beyond their noise is an outcome (WithinNoise() false), not an error.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "solver/estimation/damping_laws.h"
#include "solver/estimation/fit_data.h"
#include "solver/estimation/identify.h"
#include "solver/estimation/model_family.h"
#include "solver/estimation/result_file.h"
#include "solver/estimation/robust_fit.h"
#include "solver/workflow/campaign_input.h"
#include "solver/workflow/run_observer.h"

namespace beamid::workflow {

struct IdentifyRequest {
  std::string campaign_folder;  // holds campaign.json
  // The response channels to fit; unset: every sensor neither ignored nor
  // held out. A list that is set must name at least one channel.
  std::optional<std::vector<std::string>> fit_channels;
  std::vector<std::string> validate_channels;  // held out: predicted and compared
  std::string model = "hb";                     // the model family's name (solver::ModelFamilies())
  PhasorInput phasor_input;
  int harmonics = 5;      // H of the model (1..50)
  int fit_harmonics = 3;  // harmonics 1..K fitted (1..50, K <= H)
  solver::PhasorUncertainty phasor_uncertainty = solver::PhasorUncertainty::kPropagated;
  int starts = 0;         // further starts besides the direct estimate (0..1000)
  int workers = 0;        // worker processes for the starts (0: one per core; up to 256)
  bool fit_ei_scale = false;     // also fit a scale of the nominal bending stiffness
  bool fix_loss_factor = false;  // hold the beam's loss factor at beam_loss_factor
  bool damping_envelope = true;  // refit under the other beam damping laws
  bool robust = true;            // test the steps for outliers and refit without them
  double beam_loss_factor = 0.0;  // the loss factor's start, or its value when fixed (0..1)
  std::string output = "result.json";  // the result file written
  std::string csv_output;              // also the parameters as CSV ("": none)

  // Throws InputError naming the field (by its command-line option) and the
  // fix: a value out of range, an empty list of fitted channels, an
  // output that would replace an input (solver/workflow/output_paths.h), an
  // unknown model family, K > H. Returns the model family. The campaign
  // itself (a missing folder, an unknown channel) is checked as it is read.
  const solver::ModelFamily& Validate() const;
};

struct IdentifyOutcome {
  const solver::ModelFamily* family = nullptr;
  solver::FitData fit;                      // every fitted step (before the robust fit left any out)
  solver::IdentifyResult ordinary;          // the fit with every step
  solver::RobustFitResult robust;           // its .fit is the result (the ordinary one when nothing was left out)
  solver::DampingLawEnvelope damping_laws;  // empty when not computed
  solver::ResultFile result_file;           // as written to output
  std::string output;

  const solver::IdentifyResult& Result() const { return robust.fit; }
  // Whether the model fits the data within their noise; if not, the
  // parameters are not to be quoted (diagnose the misfit).
  bool WithinNoise() const { return robust.fit.verdict.within_noise; }
};

// Validates the request, reads the campaign and its phasors (or extracts
// them), fits, writes request.output and returns what it found. Tasks told to
// the observer: "extract" (unless phasors are given), then "identify".
IdentifyOutcome IdentifyCampaign(const IdentifyRequest& request, const RunObserver& observer = {});

}  // namespace beamid::workflow
