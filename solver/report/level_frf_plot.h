// One level's frequency response as the measured-backbone page draws it
// (solver/report/measured_backbone_report.h), in the panels of the campaign
// report's response figure (solver/report/response_plots.h): the steps'
// |X/F| and phase against frequency (dots), the cross-level single-mode fit
// regenerating the level drawn over them (a line, broken where the fit has
// no value or the phase wraps), and marked: the peak, the half-power points
// (at 1/√2 of the peak), the phase resonance (at ±90°) and each jump (a
// dashed segment from the step before it to the step after). A marker is
// drawn only where its number exists.
#pragma once

#include <string>

#include "solver/backbone/measured_backbone.h"
#include "solver/report/stacked_plot.h"

namespace beamid::solver {

// The figure's description (datablocks "measured", "fit", "fit_phase",
// "peak", "half_power", "quadrature", "jumps"); `excitation` labels X/F's unit.
StackedPlot LevelFrfPlot(const LevelResonance& level, const ExcitationLabels& excitation);

// "" when the level holds no measured point (a file written before them).
std::string LevelFrfPlotSvg(const LevelResonance& level, const ExcitationLabels& excitation);

}  // namespace beamid::solver
