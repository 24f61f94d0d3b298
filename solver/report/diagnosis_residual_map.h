// The residual maps of a diagnosis, before and after its cause: per fitted
// channel c, harmonic k and step i the whitened misfit |L⁻¹(Y_model − Y)|
// (solver/estimation/fit_data.h) of the base model and of the selected one,
// as diagnosis.json's response points hold them. The squares of a map's
// cells sum to that model's χ², so the two maps show where the cause took
// the misfit away and where some is left.
#pragma once

#include <vector>

#include "solver/diagnosis/diagnosis.h"
#include "solver/report/report_curves.h"

namespace beamid::solver {

enum class DiagnosedModel { kBase, kSelected };

// Rows "acc1 h1", … (channel-major, channels in the file's order), a column
// per step (consecutive points of one level and frequency); the held-out
// channels are left out. Empty (no rows) when the file predates the misfits.
ResidualMap DiagnosisResidualMap(const std::vector<ResponsePoint>& response, DiagnosedModel model);

// Σ of the squared cells (NaN cells skipped): the model's χ² on the map.
double SumOfSquares(const ResidualMap& map);

}  // namespace beamid::solver
