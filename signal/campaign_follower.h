// A campaign folder followed while an acquisition writes it: each look
// rereads campaign.json when it changed and hands out the steps whose
// recordings have become complete. A step counts as complete once
// campaign.json lists it and its file's size and modification time are the
// same at two looks at least stable_s apart (an acquisition that writes a
// file in pieces, or copies it in, changes one or the other meanwhile); it
// is then read once. A recording that cannot be used (clipped, cut short,
// no steady state: signal/recording.h) is handed out once as faulty, and
// read again only when its file changes (the rig measured it again). Steps
// are handed out as they complete, in whatever order that is; the index is
// their place in campaign.json. Polling, not inotify: it works the same on
// a network share, where the DAQ computer often writes.
#pragma once

#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "signal/campaign.h"
#include "signal/recording.h"
#include "signal/recording_validator.h"

namespace beamid::signal {

struct CampaignFollowerOptions {
  RecordingChecks checks;
  // A file unchanged for this long [s] between two looks is complete.
  double stable_s = 0.5;
  // campaign.json that stays invalid (bad JSON, a wrong field) for this many
  // looks in a row is an error; before that it may be half written by an
  // acquisition that does not replace it atomically.
  int invalid_looks = 5;

  // Throws InputError naming the field, its value and the allowed range.
  void Validate() const;
};

enum class FollowedStatus { kComplete, kFaulty };

struct FollowedStep {
  int index = 0;  // place in campaign.json's steps
  Step step;
  FollowedStatus status = FollowedStatus::kComplete;
  Recording recording;  // kComplete only
  std::string error;    // kFaulty: what is wrong and what to fix
  bool again = false;   // a step handed out before, whose file has changed since
};

class CampaignFollower {
 public:
  CampaignFollower(std::filesystem::path folder, const CampaignFollowerOptions& options = {});

  // One look at the folder at time now_s (any monotonic clock, in seconds):
  // the steps that have become complete since the last look. Throws
  // InputError for campaign.json invalid for invalid_looks looks in a row, a
  // step's file outside the folder, or a campaign.json that changes a
  // channel or the beam of steps already handed out.
  std::vector<FollowedStep> Look(double now_s);

  // campaign.json as last read; nullopt before it first appears.
  const std::optional<Campaign>& campaign() const { return campaign_; }
  // Steps listed whose recordings have not been handed out yet.
  int waiting() const;
  std::filesystem::path folder() const { return folder_; }

 private:
  struct FileSignature {
    std::uintmax_t size = 0;
    std::int64_t modified_ns = 0;
    bool operator==(const FileSignature&) const = default;
  };
  struct Seen {
    FileSignature signature;
    double since_s = 0.0;  // first look that saw this signature
    bool handed_out = false;
  };
  void ReadCampaignIfChanged();
  static std::optional<FileSignature> SignatureOf(const std::filesystem::path& path);

  std::filesystem::path folder_;
  CampaignFollowerOptions options_;
  std::optional<Campaign> campaign_;
  std::optional<FileSignature> campaign_signature_;
  int invalid_in_a_row_ = 0;
  std::map<std::string, Seen> seen_;  // by step file
  std::set<std::string> seen_again_;  // files handed out at least once
};

}  // namespace beamid::signal
