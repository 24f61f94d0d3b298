#include "solver/cli/format_tables.h"

#include "hb/backbone_file.h"
#include "hb/frc_file.h"
#include "solver/backbone/measured_backbone_io.h"
#include "hb/model_file.h"
#include "hb/scenario.h"
#include "solver/estimation/prediction_io.h"
#include "solver/estimation/result_io.h"
#include "hb/campaign_file.h"
#include "hb/frc_file.h"
#include "signal/phasor_set_io.h"
#include "solver/diagnosis/diagnosis_io.h"
#include "solver/workflow/batch_entry.h"

namespace beamid::cli {

const std::vector<DocumentedFormat>& DocumentedFormats() {
  static const std::vector<DocumentedFormat> formats = {
      {std::string(hb::kFrcFormat), "Frequency response curves (`beamid frc`, PREFIX.json)", hb::FrcFileFields},
      {std::string(hb::kBackboneFormat), "Model backbone (`beamid backbone` on a model, PREFIX.json)",
       hb::BackboneFileFields},
      {std::string(solver::kMeasuredBackboneFormat), "Measured backbone (`beamid backbone --measured`, <output>.json)",
       solver::MeasuredBackboneFileFields},
      {std::string(hb::kModelFileFormat), "Model file (`frc`, `backbone`; docs/model-file.md)", hb::ModelFileFields},
      {std::string(hb::kScenarioFormat), "Simulation scenario (`simulate`; docs/simulator.md)", hb::ScenarioFields},
      // estimation: result.json and the prediction file
      {std::string(solver::kResultFormat), "Identification result (`beamid identify`, result.json)",
       solver::ResultFileFields},
      {std::string(solver::kPredictionFormat), "Prediction (`beamid predict`)", solver::PredictionFileFields},
      {std::string(hb::kCampaignFileFormat), "A stepped-sine campaign (`campaign.json`, docs/campaign-format.md)",
       hb::CampaignFileFields},
      {std::string(signal::kPhasorFormat), "Phasors (`beamid extract -o`)", signal::PhasorSetFields},
      {std::string(solver::kDiagnosisFormat), "Diagnosis (`beamid diagnose`, diagnosis.json)",
       solver::DiagnosisFileFields},
      {std::string(workflow::kBatchEntryFormat), "A campaign of `beamid batch` (OUTPUT/<campaign>/batch.json; "
       "docs/batch.md)", workflow::BatchEntryFields},
  };
  return formats;
}

}  // namespace beamid::cli
