// The verdict on one step of a test that is running: is it usable, and how
// long must the next step settle and record? From the step's phasors
// (signal/phasor_set.h):
//   - settled: the extraction found no transient left in the analysed part
//     (StepQuality::unsettled false); else it is measured again with a
//     longer settle;
//   - SNR: the worst analysed channel's, against min_snr_db (a warning: the
//     phasors' σ hold the noise, and a residual that is the support's own
//     harmonics beyond those fitted would come back at every take);
//   - precision: the worst analysed channel's relative σ of its fundamental,
//         r = √((σ_re² + σ_im²)/2)/|X_1|,
//     which falls as 1/√T with the steady record's length T, so the record
//     that reaches the target r* is T·(r/r*)²;
//   - settle: the transient the extraction cut from the record's start is
//     time the rig should have waited: the next step settles that much
//     longer, times a margin (a record cut before it settled: its whole
//     length more).
#pragma once

#include <string>
#include <vector>

#include "signal/phasor_set.h"

namespace beamid::solver {

struct StepVerdictOptions {
  double target_relative_std = 1e-3;  // r* of the worst analysed channel's fundamental
  double min_snr_db = 20.0;
  double settle_margin = 1.5;  // the next settle is this times the transient seen
  double min_record_s = 0.2;
  double max_record_s = 10.0;

  // Throws InputError naming the field, its value and the allowed range.
  void Validate() const;
};

struct StepVerdict {
  bool measure_again = false;        // unsettled, or no analysed channel: the same step once more
  std::vector<std::string> reasons;  // why measure_again, one sentence each
  std::vector<std::string> warnings; // usable, but look (a jump since the step before)
  std::string worst_channel;         // the channel with the largest relative σ
  double relative_std = 0.0;         // its r
  double snr_db = 0.0;               // the worst analysed channel's
  double analysed_s = 0.0;           // the steady part the phasors rest on
  double transient_s = 0.0;          // cut from the record's start
  double record_needed_s = 0.0;      // T·(r/r*)², clamped to [min_record_s, max_record_s]
  double extra_settle_s = 0.0;       // what the next settle should add
};

// `analysed` names the response channels the analysis uses (empty: all).
// `previous`: the step measured before on the same level, or nullptr; a
// fundamental that changed by more than a factor jump_ratio since is said
// (a jump, or the branch lost) when the two are at most jump_max_step_hz
// apart: over a wider step a resonance alone grows that much (the paper's
// beam 3.5 times from 53 to 54 Hz).
StepVerdict JudgeStep(const signal::StepPhasors& step, const std::vector<std::string>& analysed,
                      const StepVerdictOptions& options, const signal::StepPhasors* previous = nullptr,
                      double jump_ratio = 1.5, double jump_max_step_hz = 0.25);

}  // namespace beamid::solver
