// `beamid backbone --measured INPUT...`: the model-free measured backbone
// (solver/backbone/measured_backbone.h) of a campaign folder, a phasor file
// of `beamid extract`, or first-harmonic tables (docs/phasor-table.md),
// written as PREFIX.json, PREFIX.csv (one row per level) and
// PREFIX_curves.csv (the single-mode fit against amplitude, and the model's
// backbone at the sensor when a result.json is given);
// scripts/plot_backbone.gp plots them. The work is workflow::MeasureBackbone;
// this prints its outcome.
#pragma once

#include "solver/cli/command_registry.h"
#include "solver/workflow/measure_backbone.h"

namespace beamid::cli {

void RunMeasuredBackbone(const workflow::MeasureBackboneRequest& request, const GlobalOptions& global);

}  // namespace beamid::cli
