#include "signal/steady_state.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <optional>
#include <vector>

#include <Eigen/Cholesky>

#include "hb/option_checks.h"
#include "signal/frequency_estimator.h"
#include "signal/input_error.h"
#include "signal/internal/harmonic_basis.h"
#include "signal/internal/text.h"

namespace beamid::signal {
namespace {

using internal::FormatNumber;

constexpr double kMinOwnFrequencySnr = 10.0;

// The residual with its content below the step's frequency removed: minus
// its moving mean over one period, which passes the band of a transient
// (near and above the step's frequency) and takes out a slow wander of the
// sensor (1/f noise, thermal drift) that no settling would remove.
Eigen::VectorXd WithoutSlowWander(const Eigen::VectorXd& residual, Eigen::Index period) {
  const Eigen::Index n = residual.size();
  Eigen::VectorXd prefix(n + 1);
  prefix(0) = 0.0;
  for (Eigen::Index i = 0; i < n; ++i) prefix(i + 1) = prefix(i) + residual(i);
  Eigen::VectorXd out(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    const Eigen::Index lo = std::max<Eigen::Index>(0, i - period / 2);
    const Eigen::Index hi = std::min(n, lo + period);
    out(i) = residual(i) - (prefix(hi) - prefix(lo)) / static_cast<double>(hi - lo);
  }
  return out;
}

// What the periodic model of one channel fitted on the reference leaves.
struct ChannelResidual {
  Eigen::VectorXd residual;
  double drift_relative = 0.0;  // |X_1(end) − X_1(start)|/|X_1| over the reference, with the drift model
};

// Residual of the periodic model fitted to rows [reference_start, N),
// extended over the record. With drift, every basis column also enters
// multiplied by the time from the reference's centre: an amplitude, phase
// or offset that changes linearly over the record (creep) is a steady state
// with drift, not a transient; and the residual's slow wander is removed.
ChannelResidual PeriodicResidual(const Eigen::Ref<const Eigen::VectorXd>& x, Eigen::Index reference_start,
                                 double sample_rate_hz, double channel_frequency_hz, int num_harmonics, bool drift) {
  const Eigen::Index n = x.size();
  const Eigen::Index reference_length = n - reference_start;
  const double centre = static_cast<double>(reference_start) + 0.5 * static_cast<double>(reference_length - 1);
  internal::HarmonicBasis basis(static_cast<int>(n), sample_rate_hz, channel_frequency_hz, num_harmonics, centre);
  Eigen::MatrixXd design = basis.matrix();
  if (drift) {
    const Eigen::Index periodic = design.cols();
    design.conservativeResize(Eigen::NoChange, 2 * periodic);
    // Time scaled to ±1/2 over the reference keeps the normal matrix well conditioned.
    const Eigen::VectorXd tau =
        (Eigen::VectorXd::LinSpaced(n, 0.0, static_cast<double>(n - 1)).array() - centre) /
        static_cast<double>(reference_length);
    design.rightCols(periodic) = design.leftCols(periodic).array().colwise() * tau.array();
  }
  const auto reference_rows = design.bottomRows(reference_length);
  const Eigen::MatrixXd normal = reference_rows.transpose() * reference_rows;
  const Eigen::VectorXd coefficients = normal.ldlt().solve(reference_rows.transpose() * x.tail(reference_length));
  ChannelResidual result;
  const auto period = std::max<Eigen::Index>(2, std::lround(sample_rate_hz / channel_frequency_hz));
  result.residual = WithoutSlowWander(x - design * coefficients, period);
  if (!drift) return result;
  const Eigen::Index periodic = design.cols() / 2;
  const std::complex<double> x1(coefficients(1), -coefficients(2));
  const std::complex<double> slope(coefficients(periodic + 1), -coefficients(periodic + 2));
  result.drift_relative = std::abs(x1) > 0.0 ? std::abs(slope) / std::abs(x1) : 0.0;
  return result;
}

// Residual mean square per block (rows) and channel (columns) of the
// periodic model fitted to rows [reference_start, N). Each channel uses its
// own refined frequency: extrapolated over the record, the frequency error of
// a noisy force would leave a residual above a clean response's noise.
// drift_relative: each channel's drift (with the drift model), else zeros.
Eigen::MatrixXd BlockMeanSquares(const Eigen::Ref<const Eigen::MatrixXd>& samples, Eigen::Index reference_start,
                                 double sample_rate_hz, double frequency_hz, int num_harmonics, Eigen::Index block,
                                 bool drift, Eigen::VectorXd& drift_relative) {
  const Eigen::Index n = samples.rows();
  const Eigen::Index reference_length = n - reference_start;
  const Eigen::Index num_blocks = n / block;
  Eigen::MatrixXd mean_squares(num_blocks, samples.cols());
  drift_relative = Eigen::VectorXd::Zero(samples.cols());
  FrequencyEstimatorOptions options;
  options.num_harmonics = num_harmonics;
  for (Eigen::Index c = 0; c < samples.cols(); ++c) {
    double channel_frequency_hz = frequency_hz;
    try {
      const FrequencyEstimate own = EstimateFrequency(samples.col(c).tail(reference_length), sample_rate_hz,
                                                      frequency_hz, options, frequency_hz);
      const double bin_hz = sample_rate_hz / static_cast<double>(reference_length);
      if (own.fundamental_amplitude > kMinOwnFrequencySnr * own.fundamental_std &&
          std::abs(own.frequency_hz - frequency_hz) < bin_hz)
        channel_frequency_hz = own.frequency_hz;
    } catch (const std::runtime_error&) {
      // No convergence: this channel has too little signal; keep the force's.
    }
    const ChannelResidual fitted =
        PeriodicResidual(samples.col(c), reference_start, sample_rate_hz, channel_frequency_hz, num_harmonics, drift);
    drift_relative(c) = fitted.drift_relative;
    const Eigen::VectorXd& residual = fitted.residual;
    for (Eigen::Index b = 0; b < num_blocks; ++b)
      mean_squares(b, c) = residual.segment(b * block, block).squaredNorm() / static_cast<double>(block);
  }
  return mean_squares;
}

double Median(std::vector<double> values) {
  auto middle = values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2);
  std::nth_element(values.begin(), middle, values.end());
  return *middle;
}

}  // namespace

void SteadyStateOptions::Validate() const {
  using namespace option_checks;
  if (!(reference_fraction > 0.0 && reference_fraction <= 1.0))
    Refuse("SteadyStateOptions.reference_fraction", FormatValue(reference_fraction), "above 0 and at most 1");
  RequirePositive("SteadyStateOptions.threshold", threshold);
  RequireAtLeast("SteadyStateOptions.settled_blocks", settled_blocks, 1);
  RequirePositive("SteadyStateOptions.min_steady_periods", min_steady_periods);
  // Below 1 every block would count as decaying, however steady.
  RequireAtLeast("SteadyStateOptions.max_decay_ratio", max_decay_ratio, 1.0);
  RequireAtLeast("SteadyStateOptions.max_passes", max_passes, 1);
  RequireNonNegative("SteadyStateOptions.relative_noise_floor", relative_noise_floor);
  RequireInRange("SteadyStateOptions.max_periodic_drop_fraction", max_periodic_drop_fraction, 0.0, 1.0);
}

namespace {

// One run of steps 1–4 (see the header), with or without the drift model.
// Returns nullopt when no steady part of min_steady_periods remains; reason
// then says what was seen, worst_channel where.
std::optional<SteadyState> Detect(const Eigen::Ref<const Eigen::MatrixXd>& samples,
                                  std::span<const std::string> channels, double sample_rate_hz, double frequency_hz,
                                  int num_harmonics, const SteadyStateOptions& options, bool drift,
                                  std::string& reason, std::string& worst_channel_name) {
  const Eigen::Index n = samples.rows();
  const double samples_per_period = sample_rate_hz / frequency_hz;
  // About one period, at least 32 samples, and at least 16 blocks per record.
  const Eigen::Index block = std::min(std::max<Eigen::Index>(std::lround(samples_per_period), 32),
                                      std::max<Eigen::Index>(n / 16, 1));
  const Eigen::Index num_blocks = n / block;
  const int below_nyquist = static_cast<int>(std::ceil(0.5 * sample_rate_hz / frequency_hz)) - 1;
  const int h = std::max(1, std::min(num_harmonics, below_nyquist));
  const double limit_factor = 1.0 + options.threshold * std::sqrt(2.0 / static_cast<double>(block));
  const Eigen::VectorXd channel_power = samples.colwise().squaredNorm().transpose() / static_cast<double>(n);
  const auto min_steady = static_cast<Eigen::Index>(std::ceil(options.min_steady_periods * samples_per_period));

  // The reference holds at least min_steady_periods: a short steady record is
  // its own reference.
  Eigen::Index reference_start =
      n - std::min(n, std::max(min_steady, static_cast<Eigen::Index>(options.reference_fraction * static_cast<double>(n))));
  SteadyState state;
  for (int pass = 0; pass < options.max_passes; ++pass) {
    if (n - reference_start < min_steady) break;
    Eigen::VectorXd drift_relative;
    const Eigen::MatrixXd mean_squares =
        BlockMeanSquares(samples, reference_start, sample_rate_hz, frequency_hz, h, block, drift, drift_relative);
    // Excess of each block over its channel's limit (> 1: not quiet).
    Eigen::MatrixXd excess(num_blocks, samples.cols());
    const Eigen::Index first_reference_block = (reference_start + block - 1) / block;
    const Eigen::Index middle_reference_block = (first_reference_block + num_blocks) / 2;
    bool reference_decays = false;
    for (Eigen::Index c = 0; c < samples.cols(); ++c) {
      std::vector<double> reference;
      for (Eigen::Index b = first_reference_block; b < num_blocks; ++b) reference.push_back(mean_squares(b, c));
      const double floor = options.relative_noise_floor * options.relative_noise_floor * channel_power(c);
      const double noise = std::max(reference.empty() ? 0.0 : Median(reference), floor);
      excess.col(c) = mean_squares.col(c) / (noise * limit_factor);
      // A residual that still falls inside the reference is a slow transient
      // taken for noise: compare the reference's halves.
      const Eigen::Index half_blocks = num_blocks - middle_reference_block;
      if (middle_reference_block - first_reference_block >= 1 && half_blocks >= 1) {
        const double early =
            mean_squares.col(c).segment(first_reference_block, middle_reference_block - first_reference_block).mean();
        const double late = mean_squares.col(c).tail(half_blocks).mean();
        if ((early + floor) > options.max_decay_ratio * (late + floor)) {
          reference_decays = true;
          worst_channel_name = channels[static_cast<std::size_t>(c)];
          reason = "residual of channel '" + worst_channel_name + "' still decays by " +
                   FormatNumber(std::round(early / late * 10.0) / 10.0) + "x between t = " +
                   FormatNumber(static_cast<double>(reference_start) / sample_rate_hz) + " s and the end";
        }
      }
    }
    if (reference_decays) {
      reference_start += (n - reference_start) / 2;
      continue;
    }
    Eigen::Index settled_block = num_blocks;
    int quiet_run = 0;
    for (Eigen::Index b = 0; b < num_blocks; ++b) {
      quiet_run = excess.row(b).maxCoeff() <= 1.0 ? quiet_run + 1 : 0;
      if (quiet_run == options.settled_blocks || (quiet_run > 0 && b == num_blocks - 1)) {
        settled_block = b + 1 - quiet_run;
        break;
      }
    }
    state.first_sample = settled_block * block;
    state.settled_after_s = static_cast<double>(state.first_sample) / sample_rate_hz;
    if (settled_block == 0) {
      state.reason = "no transient detected";
    } else {
      Eigen::Index worst_block = 0, worst_channel = 0;
      excess.topRows(std::max<Eigen::Index>(settled_block, 1)).maxCoeff(&worst_block, &worst_channel);
      worst_channel_name = channels[static_cast<std::size_t>(worst_channel)];
      state.reason = "transient dropped: residual of channel '" + worst_channel_name +
                     "' up to " + FormatNumber(std::round(excess(worst_block, worst_channel) * 10.0) / 10.0) +
                     "x the noise limit until t = " + FormatNumber(state.settled_after_s) + " s";
    }
    reason = state.reason;
    if (state.first_sample <= reference_start) {
      if (drift) {
        // The drift was measured over the reference; scaled to the part analysed.
        Eigen::Index channel = 0;
        const double over_reference = drift_relative.maxCoeff(&channel);
        state.drift_relative =
            over_reference * static_cast<double>(n - state.first_sample) / static_cast<double>(n - reference_start);
        state.drift_channel = channels[static_cast<std::size_t>(channel)];
      }
      return state;
    }
    reference_start = std::min(state.first_sample, n);
  }
  return std::nullopt;
}

}  // namespace

SteadyState DetectSteadyState(const Eigen::Ref<const Eigen::MatrixXd>& samples, std::span<const std::string> channels,
                              double sample_rate_hz, double frequency_hz, int num_harmonics, const std::string& file,
                              const SteadyStateOptions& options) {
  options.Validate();
  std::string reason, worst_channel_name;
  const std::optional<SteadyState> periodic =
      Detect(samples, channels, sample_rate_hz, frequency_hz, num_harmonics, options, false, reason, worst_channel_name);
  const Eigen::Index n = samples.rows();
  if (periodic && (!options.drift_model ||
                   static_cast<double>(periodic->first_sample) <= options.max_periodic_drop_fraction * n))
    return *periodic;
  // Much or all of the record changes: a slow creep of the amplitude or
  // phase, or low-frequency wander, may be all there is. A real transient
  // stays above the noise under the drift model too.
  std::string drift_reason, drift_channel;
  std::optional<SteadyState> drifting;
  if (options.drift_model)
    drifting = Detect(samples, channels, sample_rate_hz, frequency_hz, num_harmonics, options, true, drift_reason, drift_channel);
  if (drifting && (!periodic || drifting->first_sample < periodic->first_sample)) {
    drifting->reason = "steady with drift: the amplitude or phase of channel '" + drifting->drift_channel +
                       "' changes by " + FormatNumber(std::round(drifting->drift_relative * 1000.0) / 10.0) +
                       " % over the analysed " +
                       FormatNumber(std::round(static_cast<double>(n - drifting->first_sample) / sample_rate_hz * 100.0) /
                                    100.0) +
                       " s" + (drifting->first_sample > 0 ? "; " + drifting->reason : std::string());
    return *drifting;
  }
  if (periodic) return *periodic;
  throw InputError(file, worst_channel_name,
                   "no steady state: the response still changes near the end of the record" +
                       (reason.empty() ? std::string() : " (" + reason + ")") + "; fewer than " +
                       FormatNumber(options.min_steady_periods) + " steady periods remain",
                   "record longer after the frequency step, or wait longer before recording");
}

}  // namespace beamid::signal
