// The HTML page `beamid report` writes for a measured backbone on its own
// (the PREFIX.json of `beamid backbone --measured`, format
// "beamid-measured-backbone/1"; no model, no campaign needed): one
// self-contained file (nothing executable, no external resources) with the levels'
// phase resonances, peaks and damping ratios with their σ, every flag next
// to the number it concerns and in full below the table, the jumps, which
// levels entered the cross-level fit, the damping trend judged against a
// constant damper, the warnings, and two plots drawn by gnuplot as inline
// SVG (solver/report/gnuplot_svg.h): the backbone (frequency against
// amplitude: the fit ±1σ, each level's phase resonance, flagged levels
// marked apart) and the damping ratio against amplitude. The outcomes its
// text states are embedded as one JSON data block
// (solver/report/report_outcome.h), which the text is written from.
#pragma once

#include <string>

#include "solver/backbone/measured_backbone_io.h"

namespace beamid::solver {

// `source` names the file in the page.
std::string MeasuredBackboneHtmlReport(const MeasuredBackboneFile& file, const std::string& source);

}  // namespace beamid::solver
