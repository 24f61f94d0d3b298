#include "solver/cli/measured_backbone_command.h"

#include <fmt/core.h>

#include "solver/backbone/measured_backbone.h"
#include "solver/cli/cli_output.h"
#include "solver/report/measured_backbone_summary.h"
#include "solver/workflow/measure_backbone.h"

namespace beamid::cli {

void RunMeasuredBackbone(const workflow::MeasureBackboneRequest& request, const GlobalOptions& global) {
  const workflow::MeasureBackboneOutcome outcome = workflow::MeasureBackbone(request, CliObserver(global));
  const solver::MeasuredBackbone& measured = outcome.measured;
  const solver::ExcitationLabels excitation = solver::LabelsOf(measured.excitation_quantity);
  if (global.quiet) return;
  for (const auto& w : measured.warnings) PrintToStderr(fmt::format("beamid backbone: warning: {}\n", w));
  if (measured.excitation_quantity != "force")
    fmt::print("  excitation: {} [{}]; X/F is the {}; {}\n", excitation.control, excitation.unit, excitation.frf,
               excitation.caveat);
  for (const auto& line : solver::LevelSummaryLines(measured)) fmt::print("{}\n", line);
  for (const auto& line : solver::CrossLevelSummaryLines(measured)) fmt::print("{}\n", line);
  fmt::print("wrote {0}.json, {0}.csv and {0}_curves.csv (each flag's and jump's message and the notes are in "
             "{0}.json; 'beamid report {0}.json' draws every level)\n",
             request.output);
}

}  // namespace beamid::cli
