// Measurement artefacts: faults of the recording, not of the model, which a
// fit of physics would absorb or leave as misfit. An engineer whose fit
// fails suspects the recording first; so does the diagnosis. Each artefact
// is a model of the recorded phasors Y_rec with parameters of its own,
// applied to the beam's response Y of the base model:
//   sensor gain (channel c):         Y_rec,ck = (1 + g)·Y_ck              (a calibration off by g)
//   sensor phase delay (channel c):  Y_rec,ck = e^{−ikωτ}·Y_ck            (another filter, a late channel)
//   sensor position (channel c):     Y_rec,ck = Y_k(x_c + δ)              (glued δ from the stated place)
//   clock error (all channels):      Y_rec,k(ω_read) = Y_k(ω_read·(1 + ε)) (the acquisition's clock, or the
//                                    stated sample rate, off: every frequency read is the true one/(1 + ε))
//   outlying step i:                 Y_rec,i free (2·C·K parameters: the step carries nothing)
// Fitting one: its parameters at the base model by Gauss–Newton (closed form
// for the gain), then the base physics refitted from the base optimum on the
// data corrected by them, then the parameters once more at the refit and,
// when they moved, the physics again (block coordinate descent to the joint
// optimum), with the joint fit's uncertainties: each round's are
// conditional on the other block's values. The corrections are exact transformations of the data:
//   gain: Y' = Y/(1 + g), L⁻¹' = (1 + g)·L⁻¹;
//   delay: Y' = e^{ikωτ}·Y, L⁻¹' = L⁻¹·R(−kωτ) (R the rotation of (Re, Im));
//   position: the channel at x_c + δ;
//   clock: every step's ω' = (1 + ε)·ω (the phasors, in the channels' own
//   units, and their whitening do not depend on the time axis: an
//   accelerometer's m/s² are not clock-based);
//   step: its whitening scaled by 1e-6 (weightless, its χ² share ~1e-12,
//   without changing the steps the model holds).
// Each is then tested like a physics candidate (solver/diagnosis/diagnosis.h):
// likelihood ratio against the base with q = its parameter count, Bonferroni
// over every candidate tried, and validated on the held-out channels.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "solver/diagnosis/diagnosis.h"
#include "solver/estimation/fit_data.h"

namespace beamid::solver {

enum class ArtefactKind { kSensorGain, kSensorPhaseDelay, kSensorPosition, kOutlyingStep, kClockError };

struct MeasurementArtefact {
  ArtefactKind kind = ArtefactKind::kSensorGain;
  int channel = -1;  // index into the fit's channels (sensor artefacts)
  int step = -1;     // index into the fit's steps (outlying step)
  double value = 0.0;  // g [1], τ [s], δ [m] or ε [1]; unused for a step
};

// "sensor_gain", "sensor_phase_delay", "sensor_position", "outlying_step", "clock_error".
const char* ArtefactKindName(ArtefactKind kind);
// Its candidate name, e.g. "sensor_gain(acc2)", "outlying_step(high 53.48 Hz)" or "clock_error".
std::string ArtefactName(const FitData& fit, const MeasurementArtefact& artefact);

// The data as the artefact's model reads them (header).
FitData CorrectedData(const FitData& fit, const MeasurementArtefact& artefact);

// The artefact's parameter that best explains `fit` given the model's
// phasors `model` (per step, channels × K, of fit's channels), and its
// standard uncertainty (Gauss–Newton, scaled by max(1, reduced χ²) of that
// channel). For the position, `model_at` gives the model's phasors with the
// channel moved (it is called with candidate data); for the clock error it
// is solved anew at the scaled frequencies, on the branch the measurements
// show, with its fitted parameters, and every channel counts. Steps have no
// parameter.
struct ArtefactEstimate {
  double value = 0.0;
  double std = 0.0;
};
ArtefactEstimate EstimateGain(const FitData& fit, const std::vector<Eigen::MatrixXcd>& model, int channel);
ArtefactEstimate EstimatePhaseDelay(const FitData& fit, const std::vector<Eigen::MatrixXcd>& model, int channel);
ArtefactEstimate EstimatePosition(const FitData& fit, const FittedModel& model, int channel);
ArtefactEstimate EstimateClockError(const FitData& fit, const FittedModel& model);

// The clock error the stated frequencies show: the median over the steps of
// f_stated/f_read − 1 (0 without stated frequencies). The generator runs on
// its own clock, ppm from the stated frequency; a larger offset is the
// acquisition's (or its stated sample rate's). The clock error is tried, from
// this value, only when it exceeds 500 ppm: the model alone cannot tell a
// clock error from a modulus error (at ω(1 + ε) a model with K/(1 + ε)²
// and C/(1 + ε) gives the same accelerations).
double ClockErrorFromStatedFrequencies(const FitData& fit);

// The steps to try as outliers: those the extraction flagged as cut before
// they settled, then the base's worst steps by the robust outlier test
// (solver/estimation/robust_fit.h), at most max_steps in all.
std::vector<int> SuspectSteps(const FitData& fit, const FittedModel& base, int max_steps = 3);

// What to do on the rig when the artefact is named, with its size.
std::string ArtefactRigCheck(const FitData& fit, const MeasurementArtefact& artefact);

// Every artefact of every fitted channel, the clock error (when the stated
// frequencies show one; fitted by its profile χ², the physics refitted at
// each ε, as block coordinate descent crawls where ε and k1 both move the
// resonance), and every suspect step, fitted and
// tested against the base, Bonferroni over these and num_physics_candidates,
// and validated on the held-out channels (`validation`): an outlying step's
// held-out channels were recorded in the same faulty record, so that step
// weighs nothing there either.
CandidateRefits RefitMeasurementArtefacts(const FitData& fit, const FitData& validation, const BaseFit& base,
                                          const DiagnosisOptions& options, int num_physics_candidates,
                                          const RefitProgress& progress = {});

}  // namespace beamid::solver
