#include "signal/quality_finding.h"

#include <algorithm>

#include "signal/input_error.h"

namespace beamid::signal {

std::string_view SeverityName(Severity severity) {
  switch (severity) {
    case Severity::kNote: return "note";
    case Severity::kWarning: return "warning";
    case Severity::kError: break;
  }
  return "error";
}

std::string QualityFinding::Text(ChannelUse use) const {
  std::string text;
  if (!channel.empty()) {
    text = "channel '" + channel + "'";
    if (use == ChannelUse::kUnused) text += " (not analysed)";
    if (use == ChannelUse::kIgnored) text += " (ignored in campaign.json)";
    text += ": ";
  }
  text += problem;
  if (!fix.empty()) text += ". Fix: " + fix;
  return text;
}

Severity GradeOf(const Campaign& campaign, const std::string& channel) {
  if (channel.empty()) return Severity::kError;
  switch (campaign.Use(channel)) {
    case ChannelUse::kUsed: return Severity::kError;
    case ChannelUse::kUnused: return Severity::kWarning;
    case ChannelUse::kIgnored: break;
  }
  return Severity::kNote;
}

std::vector<QualityFinding> GradeFindings(std::vector<QualityFinding> findings, const Campaign& campaign,
                                          const std::string& file) {
  std::vector<QualityFinding> errors, rest;
  for (auto& finding : findings) {
    finding.severity = std::min(finding.severity, GradeOf(campaign, finding.channel));
    (finding.severity == Severity::kError ? errors : rest).push_back(std::move(finding));
  }
  if (errors.size() == 1) throw InputError(file, errors[0].channel, errors[0].problem, errors[0].fix);
  if (!errors.empty()) {
    std::string list = "correct each:";
    for (const auto& error : errors) list += "\n  - " + error.Text();
    throw InputError(file, "", std::to_string(errors.size()) + " problems in this recording", list);
  }
  return rest;
}

}  // namespace beamid::signal
