#include "signal/recording_validator.h"

#include <algorithm>
#include <vector>
#include <cmath>

#include "hb/option_checks.h"
#include "signal/input_error.h"
#include "signal/internal/text.h"

namespace beamid::signal {

using internal::FormatNumber;

void RecordingChecks::Validate() const {
  using namespace option_checks;
  RequirePositive("RecordingChecks.min_periods", min_periods);
  RequirePositive("RecordingChecks.max_time_deviation_samples", max_time_deviation_samples);
  if (!(sample_rate_tolerance_rel > 0.0 && sample_rate_tolerance_rel < 1.0))
    Refuse("RecordingChecks.sample_rate_tolerance_rel", FormatValue(sample_rate_tolerance_rel), "above 0 and below 1");
  // A "run" of one sample is every sample: each would be a dropout.
  RequireAtLeast("RecordingChecks.min_run_samples", min_run_samples, 2);
  RequireNonNegative("RecordingChecks.min_run_fraction_of_period", min_run_fraction_of_period);
  // At 1 or below, the 1 % of samples beyond the 99th percentile would be spikes.
  RequireAbove("RecordingChecks.max_spike_ratio", max_spike_ratio, 1.0);
}

double ValidateTimeColumn(std::span<const double> time_s, double expected_sample_rate_hz, const std::string& file,
                          int first_line, const RecordingChecks& checks) {
  checks.Validate();
  const std::size_t n = time_s.size();
  if (n < 2) throw InputError(file, "time_s", "fewer than two samples", "record the whole step");
  for (std::size_t i = 1; i < n; ++i) {
    if (!(time_s[i] > time_s[i - 1]))
      throw InputError(file, "time_s",
                       "time does not increase at line " + std::to_string(first_line + i) + " (t = " +
                           FormatNumber(time_s[i]) + " s after " + FormatNumber(time_s[i - 1]) + " s)",
                       "remove repeated rows and keep the samples in time order");
  }
  const double dt_s = (time_s[n - 1] - time_s[0]) / static_cast<double>(n - 1);
  for (std::size_t i = 0; i < n; ++i) {
    const double expected_s = time_s[0] + static_cast<double>(i) * dt_s;
    if (std::abs(time_s[i] - expected_s) > checks.max_time_deviation_samples * dt_s)
      throw InputError(file, "time_s",
                       "non-uniform sampling at line " + std::to_string(first_line + i) + " (t = " +
                           FormatNumber(time_s[i]) + " s where a uniform rate of " + FormatNumber(1.0 / dt_s) +
                           " Hz puts " + FormatNumber(expected_s) + " s; a sample is missing or the clock jumps)",
                       "export the recording at one uniform sample rate");
  }
  const double rate_hz = 1.0 / dt_s;
  if (expected_sample_rate_hz > 0.0 &&
      std::abs(rate_hz / expected_sample_rate_hz - 1.0) > checks.sample_rate_tolerance_rel)
    throw InputError(file, "time_s",
                     "the time column implies " + FormatNumber(rate_hz) + " Hz but campaign.json says sample_rate_Hz = " +
                         FormatNumber(expected_sample_rate_hz),
                     "correct sample_rate_Hz in campaign.json or the time column");
  return rate_hz;
}

void ValidateChannels(const Eigen::MatrixXd& samples, std::span<const std::string> channels, double sample_rate_hz,
                      double start_time_s, double nominal_frequency_hz, const std::string& file,
                      const RecordingChecks& checks) {
  checks.Validate();
  const Eigen::Index n = samples.rows();
  const double samples_per_period = sample_rate_hz / nominal_frequency_hz;
  const double periods = static_cast<double>(n) / samples_per_period;
  if (periods < checks.min_periods)
    throw InputError(file, "",
                     "too short: " + std::to_string(n) + " samples hold " + FormatNumber(periods) + " periods of the " +
                         FormatNumber(nominal_frequency_hz) + " Hz step",
                     "record at least " + FormatNumber(checks.min_periods) + " periods (" +
                         FormatNumber(checks.min_periods / nominal_frequency_hz) + " s) of steady response");
  const Eigen::Index min_run = std::max<Eigen::Index>(
      checks.min_run_samples,
      static_cast<Eigen::Index>(std::ceil(checks.min_run_fraction_of_period * samples_per_period)));
  auto time_at = [&](Eigen::Index i) { return FormatNumber(start_time_s + static_cast<double>(i) / sample_rate_hz); };

  for (Eigen::Index c = 0; c < samples.cols(); ++c) {
    const double* x = samples.col(c).data();
    const double max_value = samples.col(c).maxCoeff();
    const double min_value = samples.col(c).minCoeff();
    const std::string& channel = channels[static_cast<std::size_t>(c)];
    if (max_value == min_value)
      throw InputError(file, channel, "the channel is constant (" + FormatNumber(max_value) + ") over the whole record",
                       "check that the sensor is connected and its column is the right one");
    std::vector<double> deviation(x, x + n);
    std::nth_element(deviation.begin(), deviation.begin() + n / 2, deviation.end());
    const double median = deviation[static_cast<std::size_t>(n / 2)];
    for (Eigen::Index i = 0; i < n; ++i) deviation[static_cast<std::size_t>(i)] = std::abs(x[i] - median);
    const auto p99 = deviation.begin() + static_cast<std::ptrdiff_t>(0.99 * static_cast<double>(n - 1));
    std::nth_element(deviation.begin(), p99, deviation.end());
    if (*p99 > 0.0)
      for (Eigen::Index i = 0; i < n; ++i)
        if (std::abs(x[i] - median) > checks.max_spike_ratio * *p99)
          throw InputError(file, channel,
                           "spike: the sample at t = " + time_at(i) + " s (" + FormatNumber(x[i]) + ") lies " +
                               FormatNumber(std::abs(x[i] - median) / *p99) +
                               " times farther from the median than 99 % of the channel's samples",
                           "repair or remove the corrupted sample, or record the step again");
    Eigen::Index run_start = 0;
    for (Eigen::Index i = 1; i <= n; ++i) {
      if (i < n && x[i] == x[run_start]) continue;
      const Eigen::Index run = i - run_start;
      if (run >= min_run) {
        const double value = x[run_start];
        const std::string span = std::to_string(run) + " identical samples (" + FormatNumber(value) + ") from t = " +
                                 time_at(run_start) + " s to " + time_at(i - 1) + " s";
        if (value == max_value || value == min_value)
          throw InputError(file, channel, "clipped: " + span + " at the channel's extreme value",
                           "reduce the excitation level or raise the input range of this channel and record again");
        throw InputError(file, channel, "dropout: " + span,
                         "check the cable and the acquisition of this channel and record the step again");
      }
      run_start = i;
    }
  }
}

}  // namespace beamid::signal
