// Checks that a recording can represent its step, before any estimation:
//  - time: strictly increasing and uniform (every t_n within
//    max_time_deviation_samples·Δt of t_0 + n·Δt, Δt from the end points), and
//    consistent with the campaign's sample_rate_Hz when that is given. A time
//    column printed with few digits (4 decimals at 5120 Hz) is uniform when
//    every t_n, and every step t_n − t_(n−1), lies within that tolerance plus
//    half a unit of the last printed digits; Δt then comes from a
//    least-squares line (or is the campaign's sample_rate_Hz when given), and
//    a column too coarse to show a missing sample is refused;
//  - length: at least min_periods periods of the nominal frequency;
// Channel problems are findings (signal/quality_finding.h), graded by the
// channel's use, all reported together:
//  - per channel: no clipping (a run of identical samples at the channel's
//    extreme value) and no dropout (a run of identical samples elsewhere,
//    e.g. exact zeros). A run counts when it is at least
//    max(min_run_samples, min_run_fraction_of_period · samples per period)
//    long: a sine quantised to 4 significant digits repeats a value over less
//    than 0.5 % of a period at its peak, a clipped or dropped signal for far
//    longer;
//  - per channel: no spike (a sample farther from the median than
//    max_spike_ratio times the channel's 99th percentile of |x − median|): a
//    steady vibration never exceeds its own 99th percentile by more than its
//    noise, while one corrupted sample of 1000× the level shifts every
//    harmonic of the step by its size / N (an unnoticed 1.8 N error on a
//    0.5 N force). Judged only while the excitation runs (the first column;
//    signal/driven_span.h): a shaker switched off shocks the structure.
// NaN/Inf values are rejected while parsing (signal/recording.h).
#pragma once

#include <functional>
#include <span>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "signal/quality_finding.h"

namespace beamid::signal {

struct RecordingChecks {
  double min_periods = 10.0;
  double max_time_deviation_samples = 0.1;
  double sample_rate_tolerance_rel = 1e-3;
  int min_run_samples = 4;
  double min_run_fraction_of_period = 0.02;
  double max_spike_ratio = 10.0;
  // Runs of identical samples (clipping, dropouts) are judged only on a
  // channel that spans at least this many converter steps (its range over
  // its resolution); below, repeated values are quantisation of a quiet
  // signal. 64 steps: 6 bits of a converter's range.
  double min_converter_steps_for_runs = 64.0;

  // Throws InputError naming the field, its value and the allowed range.
  void Validate() const;
};

// Returns the sample rate [Hz] implied by the time column; throws InputError.
// expected_sample_rate_hz <= 0 means "not given". first_line is the file line
// of time_s[0], for messages.
double ValidateTimeColumn(std::span<const double> time_s, double expected_sample_rate_hz, const std::string& file,
                          int first_line, const RecordingChecks& checks);

// How a text file printed its time column (signal/table_reader.h).
struct PrintedTime {
  std::string column = "time_s";   // the header's name for it, for messages
  int first_line = 2;              // file line of time_s[0] when lines is empty
  std::vector<int> lines;          // file line of each sample, or empty
  // What messages call a sample's place: a text file's "line", or the
  // "sample" (0-based, with first_line 0) of a time vector in a .mat or HDF5 file.
  std::string place = "line";
  // Half a unit of each value's last printed digit [s], computed only when
  // the times are not uniform as printed; empty: the values are exact.
  std::function<std::vector<double>()> rounding_s;
};

// The same check for a printed time column: the deviations are judged
// against the tolerance plus the printed rounding (see above).
double ValidateTimeColumn(std::span<const double> time_s, double expected_sample_rate_hz, const std::string& file,
                          const PrintedTime& printed, const RecordingChecks& checks);

// The grid a channel's values lie on: the converter's step (or the printed
// resolution) and how many steps the channel spans, range/step. Values that
// lie on no grid (a 24-bit converter, printed with 9 digits) give step 0 and
// num_steps ∞; a constant channel step 0 and num_steps 0.
struct ConverterResolution {
  double step = 0.0;
  double num_steps = 0.0;
};
ConverterResolution ResolutionOf(const Eigen::Ref<const Eigen::VectorXd>& x);

// Clipping, dropout, spike and constant-channel checks of every column
// (channel names in column order): every problem found, one per kind and
// channel, naming the time and the fix, as ungraded findings
// (signal/quality_finding.h grades them). A record too short for the step
// throws InputError: nothing of it can be analysed.
std::vector<QualityFinding> CheckChannels(const Eigen::MatrixXd& samples, std::span<const std::string> channels,
                                          double sample_rate_hz, double start_time_s, double nominal_frequency_hz,
                                          const std::string& file, const RecordingChecks& checks);

}  // namespace beamid::signal
