// A stepped-sine campaign (docs/campaign-format.md, format
// "stepped-sine-campaign/1"): the beam's nominal properties, the excitation
// channel (a force, or a drive voltage or base acceleration, which only the
// model-free tools can use), the response channels, the channels to ignore
// and the list of steps (one recording per nominal generator frequency and
// level). ReadCampaign validates campaign.json
// strictly — unknown keys, missing or non-physical values, unknown quantities
// or units, duplicate channels, missing recording files — and throws
// InputError (a std::invalid_argument) naming the file, the entry and the fix.
// Values are stored in SI; each channel keeps its unit's factor to SI, which
// the recording reader applies.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "hb/beam_properties.h"
#include "hb/campaign_file.h"
#include "signal/quantity.h"
#include "signal/table_reader.h"

namespace beamid::signal {

inline constexpr std::string_view kCampaignFormat = hb::kCampaignFileFormat;

// One channel of the recordings: the excitation or a response sensor.
struct ChannelSpec {
  std::string channel;        // the channel's name; the recordings' column name unless `column(_number)` says
  double position_m = 0.0;    // x from the clamp
  Quantity quantity = Quantity::kForce;
  std::string unit;           // unit in the files, as written in campaign.json
  double to_si_factor = 1.0;  // SI value = factor · file value
  std::optional<double> mass_kg;  // sensor mass, when the engineer knows it
  // A voltage excitation's nominal force per volt (the amplifier and
  // shaker's), when the engineer knows it; labels only, never a force.
  std::optional<double> sensitivity_N_per_V;
  std::string column;     // header text of the recording column it reads ("Ch2 acc1 [g]"), "" when not given
  int column_number = 0;  // 1-based number of the recording column it reads, 0 when not given
};

// How an analysis treats a channel's problems (signal/quality_finding.h): a
// problem of a channel it uses is an error, of a channel it does not use a
// warning, of a channel campaign.json ignores a note.
enum class ChannelUse { kUsed, kUnused, kIgnored };

struct Step {
  std::string file;           // relative to the campaign folder
  double frequency_hz = 0.0;  // nominal generator frequency ("frequency_Hz")
  std::string level;          // label grouping the steps of one sweep
};

struct Campaign {
  std::filesystem::path folder;
  std::string name;
  hb::BeamProperties beam;  // loss_factor 0: campaign.json does not give one
  ChannelSpec excitation;
  std::vector<ChannelSpec> sensors;
  std::vector<Step> steps;  // in the order they were run
  std::optional<double> sample_rate_hz;  // "sample_rate_Hz", when given
  std::vector<std::string> ignored_channels;  // "ignore_channels": sensors not to judge or use
  // "recording_layout": a metadata block before the CSV recordings' header
  // and a units row under it (universal files have neither).
  TableLayout recording_layout;
  // The sensors the running analysis uses (set by the command: fitted,
  // validated, named with --channel); empty: every sensor not ignored.
  std::vector<std::string> analysed_sensors;
  // Set by ReadCampaign: the content hash of campaign.json and the
  // recordings (signal/campaign_hash.h), which every file derived from the
  // campaign carries as "campaign_sha256"; "" when not read from files.
  std::string sha256;
  // Set by ReadCampaign: what the engineer should look at but that does not
  // stop an analysis (a recording that is a byte copy of another step's),
  // one sentence each, naming the files.
  std::vector<std::string> warnings;

  // kUsed for the excitation and the analysed sensors.
  ChannelUse Use(std::string_view channel) const;
  // Sets analysed_sensors; throws InputError for a name that is no sensor,
  // or one that campaign.json ignores.
  void Analyse(const std::vector<std::string>& channels);

  // The force channel first, then the sensors in campaign order: the column
  // order of every Recording.
  std::vector<const ChannelSpec*> Channels() const;
  // Full path of a step's recording.
  std::filesystem::path StepPath(const Step& step) const { return folder / step.file; }
};

// Reads and validates folder/campaign.json; also checks that every step's
// recording exists, computes the campaign's content hash (sha256) and warns
// of a recording whose bytes are another step's. Throws InputError.
Campaign ReadCampaign(const std::filesystem::path& folder);

// The checks ReadCampaign makes of the steps' files: each lies inside the
// campaign folder (links resolved), no two steps name one file, and none is
// a folder, FIFO or device; a missing file is an error when
// missing_is_error (a campaign being written lists a step before its file
// is complete). source names campaign.json in messages. Throws InputError.
void RequireRecordingsInside(const Campaign& campaign, const std::filesystem::path& source, bool missing_is_error);

// The same validation on campaign.json text already in memory; source names
// the file in messages. Recording files are not checked.
Campaign ParseCampaign(std::string_view json_text, const std::filesystem::path& folder,
                       const std::string& source);

}  // namespace beamid::signal
