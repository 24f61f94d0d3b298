#include "solver/cli/format_tables.h"

#include "hb/frc_file.h"
#include "solver/estimation/prediction_io.h"
#include "solver/estimation/result_io.h"

namespace beamid::cli {

const std::vector<DocumentedFormat>& DocumentedFormats() {
  static const std::vector<DocumentedFormat> formats = {
      {std::string(hb::kFrcFormat), "Frequency response curves (`beamid frc`, PREFIX.json)", hb::FrcFileFields},
      // estimation: result.json and the prediction file
      {std::string(solver::kResultFormat), "Identification result (`beamid identify`, result.json)",
       solver::ResultFileFields},
      {std::string(solver::kPredictionFormat), "Prediction (`beamid predict`)", solver::PredictionFileFields},
  };
  return formats;
}

}  // namespace beamid::cli
