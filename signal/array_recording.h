// A step's recording from a MATLAB .mat file or an HDF5 file
// (signal/array_file.h): one real vector per channel, named as campaign.json
// names the channel (or as its "column" says; a name with a unit suffix,
// "acc1_g", as in a CSV header), and a time vector or a sample rate:
//  - time: a vector named time_s, t_s (seconds), time_ms, t_ms
//    (milliseconds), or time / t with its unit given by the file (the HDF5
//    attribute units = "s", the .mat variable time_units = 's');
//  - else a sample rate in Hz: a scalar sample_rate_Hz, fs or Fs (in HDF5 a
//    dataset or an attribute of the root group);
//  - else campaign.json's sample_rate_Hz (which must agree with the file's
//    rate when both are given).
// Columns and rows, double and single precision are read alike. A unit the
// file gives (HDF5 attribute "units", .mat variable <name>_units, or the
// name's suffix) must be campaign.json's, as a CSV header's must. Every
// problem is an InputError naming the file, the channel (or the time
// variable) and the fix; a channel no analysis of the run uses is left out
// with a finding instead (signal/internal/channel_defects.h), as for CSV.
// The result is validated like a CSV recording (signal/recording_validator.h);
// docs/campaign-format.md has the layout.
#pragma once

#include "signal/array_file.h"
#include "signal/campaign.h"
#include "signal/recording.h"

namespace beamid::signal {

// Throws InputError naming file.Source(), the channel and the fix.
Recording RecordingFromArrays(ArrayFile& file, const Campaign& campaign, const Step& step,
                              const RecordingChecks& checks = {});

}  // namespace beamid::signal
