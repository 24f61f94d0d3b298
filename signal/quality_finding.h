// A problem a check found in one step's recording, graded by what it does to
// the analysis: an error stops the step (its phasors would be wrong), a
// warning is printed beside the result (the result stands, the engineer
// should look), a note is recorded (nothing to do). The grade of a channel's
// problem follows the channel's use (signal/campaign.h: ChannelUse): the same
// dropout is an error on a fitted accelerometer, a warning on one no analysis
// uses, a note on one campaign.json ignores.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "signal/campaign.h"

namespace beamid::signal {

enum class Severity { kNote, kWarning, kError };

// "note", "warning", "error".
std::string_view SeverityName(Severity severity);

struct QualityFinding {
  Severity severity = Severity::kError;
  std::string channel;  // empty: the whole record
  std::string problem;
  std::string fix;

  // "channel 'acc1' (not analysed): dropout: ... Fix: ..." — the channel's
  // use is named when it lowered the grade.
  std::string Text(ChannelUse use = ChannelUse::kUsed) const;
};

// The grade of a problem of `channel` (empty: the whole record, always an
// error) under the campaign's channel uses.
Severity GradeOf(const Campaign& campaign, const std::string& channel);

// Grades every finding; throws one InputError for `file` naming every error
// (all of them, not the first alone); returns the warnings and notes.
std::vector<QualityFinding> GradeFindings(std::vector<QualityFinding> findings, const Campaign& campaign,
                                          const std::string& file);

}  // namespace beamid::signal
