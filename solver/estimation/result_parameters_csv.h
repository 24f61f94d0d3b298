// The identified parameters of a result file as a CSV table a spreadsheet
// opens (`beamid identify --csv FILE`, docs/result-format.md): one row per
// parameter with its value, standard uncertainty and 95 % interval, the part
// of the σ the residual model error adds, and — where identify refitted the
// other damping laws and the harmonic truncation — the total interval
// (statistical and model form, solver/estimation/damping_laws.h) and what it
// holds. Cells not computed are empty (hb/csv_cell.h).
#pragma once

#include <string>

#include "solver/estimation/result_file.h"

namespace beamid::solver {

std::string ResultParametersCsv(const ResultFile& file);

}  // namespace beamid::solver
