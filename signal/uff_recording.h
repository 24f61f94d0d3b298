// A step's recording from a universal file (signal/uff58.h): each dataset 58
// is one channel, matched to the campaign's channels by name, and all of them
// must share the sampling (x_min, Δx and the number of values of record 7).
// The name of a dataset is, in this order, the first that names a campaign
// channel: its ID line 1 (trimmed), its response entity name (record 6), or
// its response node and direction written "node:±dir" (e.g. "12:+Z"). Units:
// the ordinate's axis units label (record 9) when given, otherwise the unit
// campaign.json states for the channel; the ordinate's specific data type
// (8 displacement, 11 velocity, 12 acceleration, 9/13 force) must agree with
// the channel's quantity when it is not 0/1 (unknown/general). The abscissa
// must be time in s (or ms). The result is validated like a CSV recording
// (signal/recording_validator.h); docs/uff58.md has the whole mapping.
#pragma once

#include <string>
#include <vector>

#include "signal/campaign.h"
#include "signal/recording.h"
#include "signal/uff58.h"

namespace beamid::signal {

// Throws InputError naming the file, the channel and the fix.
Recording RecordingFromUff58(const std::vector<Uff58Dataset>& datasets, const Campaign& campaign, const Step& step,
                             const std::string& source, const RecordingChecks& checks = {});

}  // namespace beamid::signal
