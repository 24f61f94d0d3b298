// The channels a recording's reader found defective (signal/recording.h,
// signal/uff_recording.h, signal/array_recording.h). A problem of a channel the analysis uses stops
// the step (InputError); that of a channel it does not use (not analysed, or
// ignored in campaign.json) is a finding, graded later
// (signal/quality_finding.h), and the channel is left out of the recording:
// nothing of it is analysed, and its values are not trusted.
#pragma once

#include <algorithm>
#include <string>
#include <utility>
#include <vector>

#include "signal/campaign.h"
#include "signal/input_error.h"
#include "signal/quality_finding.h"
#include "signal/recording.h"

namespace beamid::signal::internal {

class ChannelDefects {
 public:
  ChannelDefects(const Campaign& campaign, const std::vector<const ChannelSpec*>& channels, std::string source)
      : campaign_(campaign), channels_(channels), source_(std::move(source)), dropped_(channels.size(), false) {}

  // Throws for a used channel; else records the channel's first problem.
  void Report(std::size_t channel, const std::string& problem, const std::string& fix) {
    const std::string& name = channels_[channel]->channel;
    if (GradeOf(campaign_, name) == Severity::kError) throw InputError(source_, name, problem, fix);
    if (dropped_[channel]) return;  // its first problem is the one to repair
    dropped_[channel] = true;
    findings_.push_back({Severity::kError, name, problem + "; the channel is left out of this step", fix});
  }
  bool Dropped(std::size_t channel) const { return dropped_[channel]; }
  bool Any() const { return std::find(dropped_.begin(), dropped_.end(), true) != dropped_.end(); }
  // A problem of the file that stops nothing (a column no channel uses).
  void Note(std::string problem, std::string fix) {
    findings_.push_back({Severity::kNote, "", std::move(problem), std::move(fix)});
  }
  std::vector<QualityFinding>& Findings() { return findings_; }

  // A reader's last step: the kept channels' samples (SI, one column per
  // recording.channels) are checked (CheckChannels: too short, clipping,
  // dropouts, spikes), and those findings graded with the reader's own.
  void Finish(Recording& recording, Eigen::MatrixXd samples, const Step& step, const RecordingChecks& checks) {
    std::vector<QualityFinding> findings = std::move(findings_);
    for (auto& finding : CheckChannels(samples, recording.channels, recording.sample_rate_hz, recording.start_time_s,
                                       step.frequency_hz, source_, checks))
      findings.push_back(std::move(finding));
    recording.findings = GradeFindings(std::move(findings), campaign_, source_);
    recording.samples = std::move(samples);
  }

 private:
  const Campaign& campaign_;
  const std::vector<const ChannelSpec*>& channels_;
  std::string source_;
  std::vector<bool> dropped_;
  std::vector<QualityFinding> findings_;
};

}  // namespace beamid::signal::internal
