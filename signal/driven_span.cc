#include "signal/driven_span.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "hb/option_checks.h"
#include "signal/internal/text.h"

namespace beamid::signal {

void DrivenSpanOptions::Validate() const {
  using namespace option_checks;
  RequireInRange("DrivenSpanOptions.off_fraction", off_fraction, 0.0, 1.0);
  RequireAtLeast("DrivenSpanOptions.min_off_blocks", min_off_blocks, 1);
}

std::string DrivenSpan::Describe(double sample_rate_hz, Eigen::Index num_samples) const {
  using internal::FormatNumber;
  if (!starts_late && !stops_early) return "";
  const auto seconds = [&](Eigen::Index i) {
    return FormatNumber(std::round(static_cast<double>(i) / sample_rate_hz * 1000.0) / 1000.0);
  };
  std::string text = "the excitation ";
  if (starts_late) text += "starts late";
  if (starts_late && stops_early) text += " and ";
  if (stops_early) text += "stops before the end of the record";
  return text + ": analysed only the driven part, t = " + seconds(first_sample) + " s to " + seconds(end_sample) +
         " s of " + seconds(num_samples) + " s";
}

DrivenSpan FindDrivenSpan(const Eigen::Ref<const Eigen::VectorXd>& excitation, double sample_rate_hz,
                          double frequency_hz, const DrivenSpanOptions& options) {
  options.Validate();
  const Eigen::Index n = excitation.size();
  DrivenSpan span{.first_sample = 0, .end_sample = n};
  // One period: a record of half a second must show a stop in its last 10 %.
  const Eigen::Index block = std::max<Eigen::Index>(std::lround(sample_rate_hz / frequency_hz), 16);
  const Eigen::Index num_blocks = n / block;
  if (num_blocks < 4 * options.min_off_blocks) return span;
  std::vector<double> rms(static_cast<std::size_t>(num_blocks));
  for (Eigen::Index b = 0; b < num_blocks; ++b) {
    const auto segment = excitation.segment(b * block, block);
    rms[static_cast<std::size_t>(b)] = std::sqrt((segment.array() - segment.mean()).square().mean());
  }
  // The driven level from the 90th percentile of the blocks, not their
  // median: a record that rings down for longer than it was driven (to hold
  // the whole free decay) has a median block of noise.
  std::vector<double> sorted = rms;
  const auto driven_level = sorted.begin() + (9 * (num_blocks - 1)) / 10;
  std::nth_element(sorted.begin(), driven_level, sorted.end());
  const double limit = options.off_fraction * *driven_level;
  const auto driven = [&](Eigen::Index b) { return rms[static_cast<std::size_t>(b)] >= limit; };
  Eigen::Index first = 0, last = num_blocks - 1;
  while (first < num_blocks && !driven(first)) ++first;
  while (last >= 0 && !driven(last)) --last;
  if (first > last) return span;
  // The samples after the last whole block belong to the last block's state.
  if (num_blocks - 1 - last >= options.min_off_blocks) {
    span.stops_early = true;
    span.end_sample = last * block;
  }
  if (first >= options.min_off_blocks) {
    span.starts_late = true;
    span.first_sample = (first + 1) * block;
  }
  if (span.end_sample <= span.first_sample) return DrivenSpan{.first_sample = 0, .end_sample = n};
  return span;
}

}  // namespace beamid::signal
