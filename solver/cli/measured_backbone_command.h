// `beamid backbone --measured INPUT...`: the model-free measured backbone
// (solver/backbone/measured_backbone.h) of a campaign folder, a phasor file
// of `beamid extract`, or first-harmonic tables (docs/phasor-table.md),
// written as PREFIX.json, PREFIX.csv (one row per level) and
// PREFIX_curves.csv (the single-mode fit against amplitude, and the model's
// backbone at the sensor when a result.json is given);
// scripts/plot_backbone.gp plots them. The work is workflow::MeasureBackbone;
// this prints its outcome.
#pragma once

#include <string>
#include <vector>

#include "solver/cli/command_registry.h"

namespace beamid::cli {

struct MeasuredBackboneCommandOptions {
  std::vector<std::string> inputs;  // one campaign folder or phasor file, or CSV tables (one per level)
  std::string channel;              // response channel of a campaign ("" = its first sensor)
  std::string result_file;          // identified model to overlay ("" = none)
  double position_m = -1.0;         // the tables' sensor position, for the overlay
  // MeasuredBackboneOptions::keep_flagged_levels_in_fit (--keep-flagged-levels).
  bool keep_flagged_levels = false;
  std::string output = "backbone";
};

void RunMeasuredBackbone(const MeasuredBackboneCommandOptions& options, const GlobalOptions& global);

}  // namespace beamid::cli
