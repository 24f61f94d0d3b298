// One step's recording: uniformly sampled channels in SI units, read from a
// CSV file (or a universal file, signal/uff_recording.h, or a MATLAB .mat or
// HDF5 file, signal/array_recording.h). The text goes
// through signal/table_reader.h, so the CSV may be an acquisition system's
// export: ',' ';' or tab separators, a decimal comma (with ';' or tab), a
// BOM, LF, CRLF or CR line ends, comment lines, quoted headers and units in
// the header ("acc2 [g]", "acc2 (m/s²)", "acc2_g") or in a units row under
// it, which must agree with the unit campaign.json declares, and a metadata
// block before the header (campaign.json's recording_layout). The channels of
// campaign.json may come in any column order, each found by its name or by
// the column campaign.json maps it to (header text or number); other
// columns are ignored (and listed in Recording::ignored_columns). The time
// column is in s or ms ("time_s", "t_ms", "time [ms]"), or absent when
// campaign.json gives sample_rate_Hz. Columns are reordered to
// Campaign::Channels() order: the force first, then the sensors as
// campaign.json lists them.
// ReadRecording parses with std::from_chars (no per-value allocation) and
// validates the file (signal/recording_validator.h). A problem of the file
// is an InputError naming the file, the channel and the line; the channels'
// problems are graded by the channel's use (Campaign::Use): the errors are
// thrown together in one InputError, warnings and notes are kept in
// Recording::findings. That holds for reading too: a channel the analysis
// does not use (not analysed, or in ignore_channels) whose column is missing,
// names another unit than campaign.json, or holds a NaN, a value that is no
// number or one beyond any measurement, is left out of the recording with a
// finding, where a used channel's would stop the step.
// Memory: the file's text, and the samples of the rows counted before they
// are reserved (blank and comment lines reserve nothing).
#pragma once

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>

#include "signal/campaign.h"
#include "signal/recording_validator.h"

namespace beamid::signal {

struct Recording {
  std::string file;                   // where it came from, for messages
  // Force first, then sensors: Campaign::Channels() less those left out (see above).
  std::vector<std::string> channels;
  double sample_rate_hz = 0.0;
  double start_time_s = 0.0;          // time_s of the first sample (0 without a time column)
  Eigen::MatrixXd samples;            // SI; rows = samples, one column per channel
  // Header cells no channel uses, for the caller to mention: printable
  // excerpts, valid UTF-8 whatever the file holds (signal/internal/text.h).
  std::vector<std::string> ignored_columns;
  // Graded problems of channels not analysed or ignored (errors throw).
  std::vector<QualityFinding> findings;

  int NumSamples() const { return static_cast<int>(samples.rows()); }
  double Duration_s() const { return NumSamples() / sample_rate_hz; }
  // Column of a channel, or -1.
  int ChannelIndex(std::string_view channel) const;
};

// Reads and validates campaign.folder/step.file: a universal file (.uff,
// .unv: signal/uff_recording.h), a MATLAB or HDF5 file (.mat, .h5, .hdf5:
// signal/array_recording.h) or else CSV.
Recording ReadRecording(const Campaign& campaign, const Step& step, const RecordingChecks& checks = {});

// Parses CSV text already in memory (source names it in messages) and
// validates it like ReadRecording.
Recording ParseRecording(std::string_view csv_text, const Campaign& campaign, const Step& step,
                         const std::string& source, const RecordingChecks& checks = {});

}  // namespace beamid::signal
