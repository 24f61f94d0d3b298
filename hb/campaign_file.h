// campaign.json as the file holds it (docs/campaign-format.md, format
// "stepped-sine-campaign/1"): the nominal beam, the excitation channel, the
// response channels, the steps (one recording each), the sample rate and
// the channels to ignore. One declaration of its fields drives the writer
// (hb/campaign_writer.h, `beamid simulate`) and the reader of the file's
// shape: types, required keys, unknown keys, ranges, sizes, each complaint
// an InputError naming the file, the field's path ("sensors[1].mass_kg"),
// the channel where the field belongs to one, and the fix. What the words
// mean (a quantity, a unit of it, a position on this beam, a channel named
// twice) is signal's (signal/campaign.h), which reads through this.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "hb/beam_properties.h"
#include "hb/json_schema.h"
#include "hb/version.h"

namespace beamid::hb {

inline constexpr std::string_view kCampaignFileFormat = "stepped-sine-campaign/1";

// The excitation or a response sensor, as written.
struct CampaignChannel {
  std::string channel;  // the channel's name; the recordings' column name unless one of the two last is given
  double position_m = 0.0;
  std::string quantity;  // "force", "voltage", "base_acceleration"; "acceleration", "velocity", "displacement"
  std::string unit;      // as the recordings hold it ("g", "mm/s")
  std::optional<double> mass_kg;              // a sensor's, when known
  std::optional<double> sensitivity_N_per_V;  // a voltage excitation's nominal force per volt, when known
  std::string column;     // the header text of the column it reads ("Ch2 acc1 [g]"), "" when not given
  int column_number = 0;  // the 1-based number of the column it reads, 0 when not given
};

struct CampaignStep {
  std::string file;  // relative to the campaign folder
  double frequency_hz = 0.0;
  std::string level;
};

// What precedes the data in every recording of the campaign (an export's
// metadata block and units row).
struct CampaignRecordingLayout {
  int lines_before_header = 0;
  bool units_row = false;
};

struct CampaignFile {
  std::string beamid_version = kVersion;  // of the writer; "" in a file a person wrote
  std::string name;                       // "" when the file has none
  BeamProperties beam;                    // the five keys of the nominal beam; no damping
  CampaignChannel excitation;
  std::vector<CampaignChannel> sensors;
  std::vector<CampaignStep> steps;  // in run order
  std::optional<double> sample_rate_hz;
  std::vector<std::string> ignore_channels;  // written only when there are some
  std::optional<CampaignRecordingLayout> recording_layout;  // written only when given
};

// The fields: path, type, unit, range (docs/formats.md).
std::vector<schema::FieldDoc> CampaignFileFields();

std::string CampaignFileToJson(const CampaignFile& file);
// `source` names the text in messages (the campaign.json it came from).
CampaignFile CampaignFileFromJson(const std::string& text, const std::string& source);

}  // namespace beamid::hb
