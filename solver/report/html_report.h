// The HTML report of `beamid report`: one self-contained file (no external
// resources, no scripts) with the identified parameters and their 95 %
// intervals, the fit's quality, the diagnosis summary when the input is a
// diagnosis, and plots drawn by gnuplot as inline SVG (solver/report/gnuplot_svg.h):
// frequency response curves per channel (all levels, measured points, model
// stable branches solid and unstable dashed), the backbone with the measured
// phase-resonance points, predicted vs measured time histories at the
// held-out channel, and the residual map (solver/report_curves.h).
#pragma once

#include <string>

#include "solver/report/report_curves.h"
#include "solver/report/report_input.h"

namespace beamid::solver {

std::string HtmlReport(const ReportInput& input, const ReportCurves& curves);

}  // namespace beamid::solver
