// Harmonic phasors of one step, the chain of
//   0. the part of the record during which the excitation runs
//      (signal/driven_span.h): a ring-down after the shaker stops is cut;
//   1. frequency from the force channel on the last half of the record
//      (signal/frequency_estimator.h), to locate the steady state;
//   2. steady-state detection (signal/steady_state.h) on the channels the
//      analysis uses (Campaign::Use): the transient is dropped;
//   3. frequency again, on the steady part (Gauss–Newton from step 1's value);
//   4. least-squares phasors of harmonics 1..H of every channel at that
//      frequency with their covariances (signal/harmonic_fit.h);
//   5. phase reference: Z_k = X_k·e^{−ikφ}, φ = arg F_1, so F_1 > 0. The
//      covariance of Z_k adds the reference's phase uncertainty:
//          C_Z = R C_X Rᵀ + k²·var(φ)·v vᵀ,   R = rotation by −kφ,
//          v = (Im Z_k, −Re Z_k),  var(φ) = wᵀ C_F1 w / |F_1|², w = (−sin φ, cos φ)
//      (channels' noises independent; F_1 itself keeps only its amplitude
//      variance). The time origin of step 4 drops out.
// After an excitation that stops before the record ends, each analysed
// response's ring-down is fitted as a fourth damping estimate
// (signal/free_decay.h).
// Quality: SNR per channel, THD, settling, warnings (low SNR, frequency far
// from nominal, harmonics cut at Nyquist, long transient, excitation stopping
// inside the record, drift beyond note_drift_relative, a channel resolved by
// few converter steps, whose uncertainty then includes the quantisation
// error) and notes (a small drift).
#pragma once

#include "signal/campaign.h"
#include "signal/driven_span.h"
#include "signal/free_decay.h"
#include "signal/frequency_estimator.h"
#include "signal/harmonic_fit.h"
#include "signal/phasor_set.h"
#include "signal/recording.h"
#include "signal/settling_transient.h"
#include "signal/steady_state.h"

namespace beamid::signal {

struct PhasorEstimatorOptions {
  int num_harmonics = 5;                   // H (the model uses 1–3, the diagnosis looks further)
  FrequencyEstimatorOptions frequency;     // its num_harmonics is set to H
  DrivenSpanOptions driven_span;
  FreeDecayOptions free_decay;
  SteadyStateOptions steady_state;
  double warn_snr_db = 20.0;               // warn when a channel's SNR is lower
  double warn_frequency_offset_rel = 0.01; // warn when |f/f_nominal − 1| is larger
  double warn_transient_fraction = 0.5;    // warn when more of the record was dropped
  double min_force_snr = 10.0;             // |F_1|/σ(F_1) below this: no excitation found
  double note_drift_relative = 0.05;       // a steady state with drift up to this is a note, beyond a warning
  // A channel spanning fewer converter steps gets the quantisation error in
  // its uncertainty and a warning (signal/recording_validator.h).
  double min_converter_steps = 64.0;
  // A record cut before it settled gets the change between its analysed
  // part's halves in its phasors' uncertainty (signal/settling_uncertainty.h);
  // off: only the warning (to see what the fit makes of it unweighed).
  bool settling_uncertainty = true;
  // Ringing left by the frequency step is fitted out of every record where
  // it is significant (signal/settling_transient.h). Off by default: on the
  // simulator's friction campaign it brings the ringing steps' phasors to
  // the settled ones (rms z 7.3 → 1.3) but, with them weighed less, the
  // steps near the jump that approach their state too slowly to be seen
  // ringing pull the fit further (docs/signal.md, step 7).
  bool settling_transient = false;
  SettlingTransientOptions transient;

  // Throws InputError naming the field, its value and the allowed range.
  void Validate() const;
};

// Recording columns in Campaign::Channels() order (as ReadRecording returns),
// possibly less channels the analysis does not use that their file could
// not give: the step's responses are then those it holds.
// Throws InputError for records that cannot represent the step (no steady
// state, no excitation at the nominal frequency), std::runtime_error when the
// frequency iteration fails.
StepPhasors EstimateStepPhasors(const Recording& recording, const Campaign& campaign, const Step& step,
                                const PhasorEstimatorOptions& options = {});

// Step 5 alone: rotates the fit of a set of channels to the reference
// channel's fundamental and packs it (channel metadata from specs, same order
// as fit.channels). Exposed for tests and for callers with their own fit.
std::vector<ChannelPhasors> ReferencePhasors(const HarmonicFit& fit, std::size_t reference_channel,
                                             const std::vector<const ChannelSpec*>& specs);

}  // namespace beamid::signal
