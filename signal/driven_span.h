// The part of a record during which the excitation runs. A shaker switched
// off before the recording ends (or switched on after it starts) leaves a
// ring-down (or rest) that is no steady state of the step: fitted with the
// driven part it drags every phasor towards zero and the SNR down, without
// an error. Method: the excitation channel's RMS about its mean in blocks of
// one period; blocks below off_fraction of the 90th percentile of the block
// RMS (the driven level while at least a tenth of the record is driven) are
// undriven. Undriven blocks at the end (or start), at least min_off_blocks of
// them, are cut, and with them the block in which the excitation stops (or
// starts), which holds the switching transient.
#pragma once

#include <string>

#include <Eigen/Core>

namespace beamid::signal {

struct DrivenSpanOptions {
  double off_fraction = 0.2;
  int min_off_blocks = 2;

  // Throws InputError naming the field, its value and the allowed range.
  void Validate() const;
};

struct DrivenSpan {
  Eigen::Index first_sample = 0;
  Eigen::Index end_sample = 0;  // one past the last driven sample
  bool starts_late = false;
  bool stops_early = false;
  std::string Describe(double sample_rate_hz, Eigen::Index num_samples) const;  // empty when the whole record is driven
};

DrivenSpan FindDrivenSpan(const Eigen::Ref<const Eigen::VectorXd>& excitation, double sample_rate_hz,
                          double frequency_hz, const DrivenSpanOptions& options = {});

}  // namespace beamid::signal
