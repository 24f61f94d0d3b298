#include "solver/cli/format_tables.h"

#include "hb/campaign_file.h"
#include "hb/frc_file.h"
#include "signal/phasor_set_io.h"

namespace beamid::cli {

const std::vector<DocumentedFormat>& DocumentedFormats() {
  static const std::vector<DocumentedFormat> formats = {
      {std::string(hb::kFrcFormat), "Frequency response curves (`beamid frc`, PREFIX.json)", hb::FrcFileFields},
      {std::string(hb::kCampaignFileFormat), "A stepped-sine campaign (`campaign.json`, docs/campaign-format.md)",
       hb::CampaignFileFields},
      {std::string(signal::kPhasorFormat), "Phasors (`beamid extract -o`)", signal::PhasorSetFields},
  };
  return formats;
}

}  // namespace beamid::cli
