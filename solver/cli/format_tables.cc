#include "solver/cli/format_tables.h"

#include "hb/frc_file.h"
#include "solver/diagnosis/diagnosis_io.h"

namespace beamid::cli {

const std::vector<DocumentedFormat>& DocumentedFormats() {
  static const std::vector<DocumentedFormat> formats = {
      {std::string(hb::kFrcFormat), "Frequency response curves (`beamid frc`, PREFIX.json)", hb::FrcFileFields},
      {std::string(solver::kDiagnosisFormat), "Diagnosis (`beamid diagnose`, diagnosis.json)",
       solver::DiagnosisFileFields},
  };
  return formats;
}

}  // namespace beamid::cli
