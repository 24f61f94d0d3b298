#include "solver/cli/format_tables.h"

#include "hb/frc_file.h"

namespace beamid::cli {

const std::vector<DocumentedFormat>& DocumentedFormats() {
  static const std::vector<DocumentedFormat> formats = {
      {std::string(hb::kFrcFormat), "Frequency response curves (`beamid frc`, PREFIX.json)", hb::FrcFileFields},
  };
  return formats;
}

}  // namespace beamid::cli
