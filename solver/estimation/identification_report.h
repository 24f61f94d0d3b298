// result.json of `beamid identify`: the identified parameters with their
// uncertainty, the fit's quality per channel, harmonic and level, the
// prediction error at held-out channels, and everything `beamid predict`
// needs to rebuild the model and its steady states (format
// "beamid-result/1", documented in the README).
#pragma once

#include <string>

#include <nlohmann/json.hpp>

#include "solver/estimation/fit_data.h"
#include "solver/estimation/fit_problem.h"
#include "solver/estimation/identify.h"

namespace beamid::solver {

struct ReportContext {
  std::string campaign_folder;
  std::string campaign_name;
  std::string model_kind = "hb";  // "hb" or "ms": which model `problem` is
};

// `problem` must be the problem whose variables result.x are (its internal
// scales set by FeasiblePoint at the best start); `validation` holds the
// held-out channels' data (no channels: no validation section).
nlohmann::json IdentificationReport(const FitData& fit, const FitData& validation, FitProblem& problem,
                                    const IdentifyResult& result, const ReportContext& context);

}  // namespace beamid::solver
