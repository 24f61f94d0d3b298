#include "signal/recording_validator.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

#include "hb/option_checks.h"
#include "signal/driven_span.h"
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
  RequireNonNegative("RecordingChecks.min_converter_steps_for_runs", min_converter_steps_for_runs);
}

double ValidateTimeColumn(std::span<const double> time_s, double expected_sample_rate_hz, const std::string& file,
                          int first_line, const RecordingChecks& checks) {
  PrintedTime printed;
  printed.first_line = first_line;
  return ValidateTimeColumn(time_s, expected_sample_rate_hz, file, printed, checks);
}

double ValidateTimeColumn(std::span<const double> time_s, double expected_sample_rate_hz, const std::string& file,
                          const PrintedTime& printed, const RecordingChecks& checks) {
  checks.Validate();
  const std::string& column = printed.column;
  auto line = [&](std::size_t i) {
    return printed.place + " " +
           std::to_string(printed.lines.empty() ? printed.first_line + static_cast<int>(i) : printed.lines[i]);
  };
  const std::size_t n = time_s.size();
  if (n < 2) throw InputError(file, column, "fewer than two samples", "record the whole step");
  std::vector<double> rounding_values;
  bool rounding_known = false;
  auto rounding_of = [&]() -> std::span<const double> {
    if (!rounding_known && printed.rounding_s) rounding_values = printed.rounding_s();
    rounding_known = true;
    return rounding_values;
  };
  auto too_coarse = [&](double dt_s, double max_pair_s) {
    return InputError(file, column,
                      "the time column is printed with too few digits to show a missing sample at " +
                          FormatNumber(1.0 / dt_s) + " Hz (its values are rounded by up to " +
                          FormatNumber(0.5 * max_pair_s) + " s, a sample lasts " + FormatNumber(dt_s) + " s)",
                      "export the time with more decimals, or leave the time column out and give sample_rate_Hz in "
                      "campaign.json");
  };
  for (std::size_t i = 1; i < n; ++i) {
    if (time_s[i] == time_s[i - 1] && !rounding_of().empty() && time_s[n - 1] > time_s[0]) {
      const std::span<const double> rounding = rounding_of();
      const double dt_s = (time_s[n - 1] - time_s[0]) / static_cast<double>(n - 1);
      const double pair_s = rounding[i] + rounding[i - 1];
      if (pair_s >= (1.0 - 2.0 * checks.max_time_deviation_samples) * dt_s) throw too_coarse(dt_s, pair_s);
    }
    if (!(time_s[i] > time_s[i - 1]))
      throw InputError(file, column,
                       "time does not increase at " + line(i) + " (t = " + FormatNumber(time_s[i]) +
                           " s after " + FormatNumber(time_s[i - 1]) + " s)",
                       "remove repeated rows and keep the samples in time order");
  }
  const double tolerance = checks.max_time_deviation_samples;
  auto check_rate = [&](double rate_hz) {
    if (expected_sample_rate_hz > 0.0 &&
        std::abs(rate_hz / expected_sample_rate_hz - 1.0) > checks.sample_rate_tolerance_rel)
      throw InputError(file, column,
                       "the time column implies " + FormatNumber(rate_hz) +
                           " Hz but campaign.json says sample_rate_Hz = " + FormatNumber(expected_sample_rate_hz),
                       "correct sample_rate_Hz in campaign.json or the time column");
  };
  auto non_uniform = [&](std::size_t i, double expected_s, double rate_hz, const std::string& why) {
    return InputError(file, column,
                      "non-uniform sampling at " + line(i) + " (t = " + FormatNumber(time_s[i]) +
                          " s where a uniform rate of " + FormatNumber(rate_hz) + " Hz puts " +
                          FormatNumber(expected_s) + " s" + why +
                          "; a sample is missing or the clock jumps)",
                      "export the recording at one uniform sample rate");
  };
  const double dt_s = (time_s[n - 1] - time_s[0]) / static_cast<double>(n - 1);
  std::size_t first_off = n;
  for (std::size_t i = 0; i < n && first_off == n; ++i)
    if (std::abs(time_s[i] - (time_s[0] + static_cast<double>(i) * dt_s)) > tolerance * dt_s) first_off = i;
  if (first_off == n) {  // uniform as printed: Δt from the end points
    const double rate_hz = 1.0 / dt_s;
    check_rate(rate_hz);
    return rate_hz;
  }
  const std::span<const double> rounding = rounding_of();
  const double max_rounding = rounding.empty() ? 0.0 : *std::max_element(rounding.begin(), rounding.end());
  if (max_rounding <= 0.0)
    throw non_uniform(first_off, time_s[0] + static_cast<double>(first_off) * dt_s, 1.0 / dt_s, "");

  // Printed with few digits: judge against the rounding, Δt by least squares.
  const double mean_index = 0.5 * static_cast<double>(n - 1);
  double mean_t = 0.0;
  for (const double t : time_s) mean_t += t;
  mean_t /= static_cast<double>(n);
  double sxy = 0.0, sxx = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const double di = static_cast<double>(i) - mean_index;
    sxy += di * (time_s[i] - mean_t);
    sxx += di * di;
  }
  const double slope_s = sxy / sxx;
  const double rate_hz = 1.0 / slope_s;
  double max_pair = 0.0;
  for (std::size_t i = 1; i < n; ++i) max_pair = std::max(max_pair, rounding[i] + rounding[i - 1]);
  if (max_pair >= (1.0 - 2.0 * tolerance) * slope_s) throw too_coarse(slope_s, max_pair);
  const double line_error_s = 2.0 * max_rounding / std::sqrt(static_cast<double>(n));
  // A missing sample shows first as one step of two periods: point at it.
  for (std::size_t i = 1; i < n; ++i)
    if (std::abs(time_s[i] - time_s[i - 1] - slope_s) > 2.0 * tolerance * slope_s + rounding[i] + rounding[i - 1])
      throw non_uniform(i, time_s[i - 1] + slope_s, rate_hz,
                        ", one period after the previous sample beyond the ±" + FormatNumber(rounding[i]) +
                            " s rounding of its printed digits");
  for (std::size_t i = 0; i < n; ++i) {
    const double expected_s = mean_t + (static_cast<double>(i) - mean_index) * slope_s;
    if (std::abs(time_s[i] - expected_s) > tolerance * slope_s + rounding[i] + line_error_s)
      throw non_uniform(i, expected_s, rate_hz,
                        ", beyond the ±" + FormatNumber(rounding[i]) + " s rounding of its printed digits");
  }
  check_rate(rate_hz);
  // The campaign's rate is exact where the printed times are not.
  return expected_sample_rate_hz > 0.0 ? expected_sample_rate_hz : rate_hz;
}

ConverterResolution ResolutionOf(const Eigen::Ref<const Eigen::VectorXd>& x) {
  std::vector<double> values(x.data(), x.data() + x.size());
  std::sort(values.begin(), values.end());
  values.erase(std::unique(values.begin(), values.end()), values.end());
  if (values.size() < 2) return {.step = 0.0, .num_steps = 0.0};
  double step = std::numeric_limits<double>::infinity();
  for (std::size_t i = 1; i < values.size(); ++i) step = std::min(step, values[i] - values[i - 1]);
  // 1e-3 of a step: values printed in decimal sit on the grid to far better.
  for (double v : values) {
    const double steps = (v - values.front()) / step;
    if (std::abs(steps - std::round(steps)) > 1e-3)
      return {.step = 0.0, .num_steps = std::numeric_limits<double>::infinity()};
  }
  return {.step = step, .num_steps = (values.back() - values.front()) / step};
}

std::vector<QualityFinding> CheckChannels(const Eigen::MatrixXd& samples, std::span<const std::string> channels,
                                          double sample_rate_hz, double start_time_s, double nominal_frequency_hz,
                                          const std::string& file, const RecordingChecks& checks) {
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
  std::vector<QualityFinding> findings;
  const auto found = [&](const std::string& channel, std::string problem, std::string fix) {
    findings.push_back({Severity::kError, channel, std::move(problem), std::move(fix)});
  };

  // Spikes are judged where the excitation runs (the first column): the
  // shock of a shaker switched off, and the ring-down after it, are no
  // corrupted samples (signal/driven_span.h).
  const DrivenSpan driven = FindDrivenSpan(samples.col(0), sample_rate_hz, nominal_frequency_hz);
  for (Eigen::Index c = 0; c < samples.cols(); ++c) {
    const double* x = samples.col(c).data();
    const double max_value = samples.col(c).maxCoeff();
    const double min_value = samples.col(c).minCoeff();
    const std::string& channel = channels[static_cast<std::size_t>(c)];
    if (max_value == min_value) {
      found(channel, "the channel is constant (" + FormatNumber(max_value) + ") over the whole record",
            "check that the sensor is connected and its column is the right one");
      continue;
    }
    std::vector<double> deviation(x + driven.first_sample, x + driven.end_sample);
    const auto m = static_cast<Eigen::Index>(deviation.size());
    std::nth_element(deviation.begin(), deviation.begin() + m / 2, deviation.end());
    const double median = deviation[static_cast<std::size_t>(m / 2)];
    for (Eigen::Index i = 0; i < m; ++i)
      deviation[static_cast<std::size_t>(i)] = std::abs(x[driven.first_sample + i] - median);
    const auto p99 = deviation.begin() + static_cast<std::ptrdiff_t>(0.99 * static_cast<double>(m - 1));
    std::nth_element(deviation.begin(), p99, deviation.end());
    Eigen::Index spikes = 0, first_spike = 0;
    if (*p99 > 0.0)
      for (Eigen::Index i = driven.first_sample; i < driven.end_sample; ++i)
        if (std::abs(x[i] - median) > checks.max_spike_ratio * *p99 && spikes++ == 0) first_spike = i;
    if (spikes > 0)
      found(channel,
            (spikes == 1 ? std::string("spike: the sample") : std::to_string(spikes) + " spikes, the first") +
                " at t = " + time_at(first_spike) + " s (" + FormatNumber(x[first_spike]) + ") lies " +
                FormatNumber(std::abs(x[first_spike] - median) / *p99) +
                " times farther from the median than 99 % of the channel's samples",
            "repair or remove the corrupted samples, or record the step again");
    // A quiet channel resolved by a few steps of the converter (a sensor
    // that is not excited much, read on a range set for more) repeats its
    // values for many samples: that is quantisation, not a dropout, and its
    // extremes repeat without clipping. Clipping and dropouts show on a
    // channel that spans many converter steps.
    if (ResolutionOf(samples.col(c)).num_steps < checks.min_converter_steps_for_runs) continue;
    Eigen::Index run_start = 0;
    bool clipped = false, dropout = false;
    for (Eigen::Index i = 1; i <= n; ++i) {
      if (i < n && x[i] == x[run_start]) continue;
      const Eigen::Index run = i - run_start;
      if (run >= min_run) {
        const double value = x[run_start];
        const std::string span = std::to_string(run) + " identical samples (" + FormatNumber(value) + ") from t = " +
                                 time_at(run_start) + " s to " + time_at(i - 1) + " s";
        // The first run of each kind: one line per problem, not per run.
        if ((value == max_value || value == min_value) && !std::exchange(clipped, true))
          found(channel, "clipped: " + span + " at the channel's extreme value",
                "reduce the excitation level or raise the input range of this channel and record again");
        else if (value != max_value && value != min_value && !std::exchange(dropout, true))
          found(channel, "dropout: " + span,
                "check the cable and the acquisition of this channel and record the step again");
      }
      run_start = i;
    }
  }
  return findings;
}

}  // namespace beamid::signal
