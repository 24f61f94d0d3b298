// The measured backbone as a CSV table a spreadsheet opens: one row per level
// (PREFIX.csv of `beamid backbone --measured`, docs/backbone.md) with each
// estimate and its σ. A number that is not estimated, or not finite (an
// infinite σ, a regeneration of a step with no response), is an empty cell
// (hb/csv_cell.h).
#pragma once

#include <string>

#include "solver/backbone/measured_backbone.h"

namespace beamid::solver {

// The per-level table, header first, labelled for what drives the levels.
std::string MeasuredLevelsCsv(const MeasuredBackbone& measured);

}  // namespace beamid::solver
