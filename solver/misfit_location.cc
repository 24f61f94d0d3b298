#include "solver/misfit_location.h"

#include <stdexcept>

namespace beamid::solver {

MisfitLocation LocateMisfit(const FitData& data, const std::vector<Eigen::MatrixXcd>& model, int fitted_harmonics,
                            const hb::LinearBeamModel& reference_beam, const MisfitLocationOptions& options) {
  (void)data, (void)model, (void)fitted_harmonics, (void)reference_beam, (void)options;
  throw std::runtime_error("LocateMisfit: not implemented yet");
}

LoopEvidence AnalyseSupportLoops(const FitData& data, const hb::LinearBeamModel& reference_beam,
                                 double family_significance) {
  (void)data, (void)reference_beam, (void)family_significance;
  throw std::runtime_error("AnalyseSupportLoops: not implemented yet");
}

nlohmann::json ToJson(const MisfitLocation&) { return nlohmann::json::object(); }
nlohmann::json ToJson(const LoopEvidence&) { return nlohmann::json::object(); }

}  // namespace beamid::solver
