// The HTML report of `beamid report`: one self-contained file (no external
// resources, nothing executable) with the identified parameters and their 95 %
// intervals, the fit's quality, the diagnosis summary when the input is a
// diagnosis, and plots drawn by gnuplot as inline SVG (solver/report/gnuplot_svg.h):
// frequency response curves per channel (solver/report/response_plots.h:
// |X₁|, |X₁|/|F₁| and phase of every level, measured points, model stable
// branches solid and unstable dashed; harmonics 2 and 3), the backbone with the measured
// phase-resonance points, predicted vs measured time histories at the
// held-out channel, and the residual map (solver/report_curves.h). The
// outcomes its text states are embedded as one JSON data block
// (solver/report/report_outcome.h), which the text is written from.
#pragma once

#include <string>

#include "solver/report/report_curves.h"
#include "solver/report/report_input.h"

namespace beamid::solver {

struct HtmlReportOptions {
  bool log_amplitude = false;  // |X₁| on a logarithmic axis (|X₁|/|F₁| and harmonics 2, 3 always are)
};

std::string HtmlReport(const ReportInput& input, const ReportCurves& curves, const HtmlReportOptions& options = {});

}  // namespace beamid::solver
