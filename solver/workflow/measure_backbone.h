// The measured-backbone use case (`beamid backbone --measured`): the
// model-free backbone and damping against amplitude of a stepped-sine test
// (solver/backbone/measured_backbone.h), from a campaign folder, a phasor
// file of `beamid extract` or first-harmonic tables (docs/phasor-table.md),
// with an identified model's backbone at the sensor beside it when a
// result.json is given; written as PREFIX.json, PREFIX.csv (one row per
// level) and PREFIX_curves.csv (the single-mode fit against amplitude and
// the model's backbone). Everything the command prints is in the outcome.
#pragma once

#include <string>
#include <vector>

#include "signal/phasor_table.h"
#include "solver/backbone/measured_backbone.h"
#include "solver/estimation/sensor_backbone.h"
#include "solver/workflow/run_observer.h"

namespace beamid::workflow {

struct MeasureBackboneRequest {
  // One campaign folder or phasor file, or CSV tables (one per level).
  std::vector<std::string> inputs;
  // Response channel of a campaign or phasor file ("": its first sensor not ignored, told as a note); of a
  // campaign, it is the one analysed sensor: the other sensors' problems only warn (signal::Campaign::Use).
  std::string channel;
  // Of a campaign: leave out (and warn of) the steps whose recordings hold errors (--skip-bad-steps).
  bool skip_bad_steps = false;
  std::string result_file;  // identified model to overlay ("": none)
  double position_m = -1.0;  // the tables' sensor position for the overlay (< 0: not given; else 0..100)
  // Of CSV tables: an export's metadata block and units row (--lines-before-header, --units-row) and columns named
  // by the user (--column ROLE=COLUMN); a campaign declares its layout in campaign.json.
  signal::PhasorTableOptions table;
  // MeasuredBackboneOptions::keep_flagged_levels_in_fit (--keep-flagged-levels).
  bool keep_flagged_levels = false;
  std::string output = "backbone";  // the prefix of the three files
  // Also each level as a universal file <label>.uff in this folder, its force spectrum and frequency response
  // (signal/uff58_export.h; "": none).
  std::string uff_folder;

  // Throws InputError naming the field (by its command-line option) and the
  // fix: no input, a position out of range, an output that is an input or
  // would replace one (solver/workflow/output_paths.h). The inputs themselves
  // are checked as they are read.
  void Validate() const;
};

struct MeasureBackboneOutcome {
  solver::MeasuredBackbone measured;
  std::string channel;  // the analysed response channel
  std::vector<solver::SensorBackbonePoint> model_backbone;  // empty without a result file
  std::string output;   // the prefix written
};

// Validates the request, reads the levels (extracting a campaign's
// harmonics 1..3), analyses them, writes the three files and returns what it
// found.
MeasureBackboneOutcome MeasureBackbone(const MeasureBackboneRequest& request, const RunObserver& observer = {});

// What controls a level, in the words of its excitation ("force", "voltage",
// "base acceleration", or the control a level of tables names).
std::string LevelControlText(const solver::MeasuredBackbone& measured, const solver::LevelResonance& level);

}  // namespace beamid::workflow
