// The measured backbone as CSV tables a spreadsheet opens: one row per level
// (PREFIX.csv of `beamid backbone --measured`, docs/phasor-table.md) with each
// estimate and its σ. A number that is not estimated, or not finite (an
// infinite σ, a regeneration of a step with no response), is an empty cell:
// never "inf" or "nan", which a reader would take for a value.
#pragma once

#include <string>
#include <string_view>

#include "solver/backbone/measured_backbone.h"

namespace beamid::solver {

// `value` in `format` (a fmt format for one number), or "" when it is not finite.
std::string CsvNumber(double value, std::string_view format);

// The per-level table, header first, labelled for what drives the levels.
std::string MeasuredLevelsCsv(const MeasuredBackbone& measured);

}  // namespace beamid::solver
