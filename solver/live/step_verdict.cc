#include "solver/live/step_verdict.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "hb/option_checks.h"

namespace beamid::solver {

void StepVerdictOptions::Validate() const {
  option_checks::RequireInRange("--phasor-target", target_relative_std, 1e-9, 1.0);
  option_checks::RequireInRange("min_snr_db", min_snr_db, -100.0, 300.0);
  option_checks::RequireInRange("settle_margin", settle_margin, 1.0, 100.0);
  option_checks::RequireInRange("--min-record", min_record_s, 1e-3, 3600.0);
  option_checks::RequireInRange("max_record_s", max_record_s, min_record_s, 3600.0);
}

namespace {

bool Analysed(const std::vector<std::string>& analysed, const std::string& channel) {
  return analysed.empty() || std::find(analysed.begin(), analysed.end(), channel) != analysed.end();
}

double RelativeStd(const signal::ChannelPhasors& channel) {
  const signal::HarmonicPhasor& x1 = channel.Harmonic(1);
  const double sigma = std::sqrt(0.5 * (x1.std_real * x1.std_real + x1.std_imag * x1.std_imag));
  return x1.Amplitude() > 0.0 ? sigma / x1.Amplitude() : INFINITY;
}

}  // namespace

StepVerdict JudgeStep(const signal::StepPhasors& step, const std::vector<std::string>& analysed,
                      const StepVerdictOptions& options, const signal::StepPhasors* previous, double jump_ratio,
                      double jump_max_step_hz) {
  options.Validate();
  StepVerdict verdict;
  verdict.analysed_s = step.quality.analysed_duration_s;
  verdict.transient_s = step.quality.settled_after_s;
  verdict.snr_db = INFINITY;
  for (const signal::ChannelPhasors& channel : step.responses) {
    if (!Analysed(analysed, channel.channel)) continue;
    const double r = RelativeStd(channel);
    if (verdict.worst_channel.empty() || r > verdict.relative_std) {
      verdict.worst_channel = channel.channel;
      verdict.relative_std = r;
    }
    verdict.snr_db = std::min(verdict.snr_db, channel.snr_db);
    if (previous && std::abs(step.nominal_frequency_hz - previous->nominal_frequency_hz) <= jump_max_step_hz) {
      const signal::ChannelPhasors* before = previous->Find(channel.channel);
      if (before && before->Harmonic(1).Amplitude() > 0.0) {
        const double ratio = channel.Harmonic(1).Amplitude() / before->Harmonic(1).Amplitude();
        if (ratio > jump_ratio || ratio < 1.0 / jump_ratio)
          verdict.warnings.push_back(fmt::format(
              "{}'s fundamental changed by a factor {:.3g} since the step at {:.4g} Hz: a jump between the two "
              "steps (measure between them from the side the sweep came from)",
              channel.channel, ratio, previous->nominal_frequency_hz));
      }
    }
  }
  if (verdict.worst_channel.empty()) {
    verdict.measure_again = true;
    verdict.reasons.push_back("the record holds none of the analysed channels");
    return verdict;
  }
  if (step.quality.unsettled) {
    verdict.measure_again = true;
    verdict.reasons.push_back(fmt::format(
        "not settled: {}'s fundamental still changed by {:.2g} (relative) across the record; settle longer",
        step.quality.unsettled_channel, step.quality.unsettled_change_relative));
    verdict.extra_settle_s = options.settle_margin * (verdict.transient_s + verdict.analysed_s);
  } else {
    verdict.extra_settle_s = options.settle_margin * verdict.transient_s;
  }
  // Not measured again: a low SNR that is the support's own higher harmonics
  // (friction) would come back at every take; the phasors' σ carry the noise.
  if (verdict.snr_db < options.min_snr_db)
    verdict.warnings.push_back(fmt::format("SNR {:.1f} dB below {:.0f} dB ({}): check the sensor, or raise the level",
                                           verdict.snr_db, options.min_snr_db, verdict.worst_channel));
  const double ratio = verdict.relative_std / options.target_relative_std;
  const double needed = std::isfinite(ratio) ? verdict.analysed_s * ratio * ratio : options.max_record_s;
  verdict.record_needed_s = std::clamp(needed, options.min_record_s, options.max_record_s);
  return verdict;
}

}  // namespace beamid::solver
