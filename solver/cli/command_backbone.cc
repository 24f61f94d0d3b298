// beamid backbone: the model's backbone — resonance frequency against
// amplitude — by exact harmonic balance (phase resonance), with the paper's
// corrected multiple-scales backbone beside it for a polynomial support; or,
// with --measured, the measured backbone of a test (measured_backbone_command.h).
// The work is workflow::TraceModelBackbone; this prints its outcome and maps
// a backbone that stopped early to exit 3 (after writing it).
#include <numbers>

#include <fmt/core.h>

#include "hb/errors.h"
#include "solver/cli/cli_output.h"
#include "solver/cli/command_registry.h"
#include "solver/cli/measured_backbone_command.h"
#include "solver/workflow/trace_model_backbone.h"

namespace beamid::cli {
namespace {

void RunBackbone(const workflow::TraceBackboneRequest& request, const GlobalOptions& global) {
  const workflow::TraceBackboneOutcome outcome = workflow::TraceModelBackbone(request, CliObserver(global));
  const hb::BackboneSummary& summary = outcome.summary;
  if (!global.quiet && !summary.points.empty()) {
    const auto& first = summary.points.front();
    const auto& last = summary.points.back();
    fmt::print("  backbone: {:.3f} Hz at |θ1| = {:.1e} rad → {:.3f} Hz at {:.1e} rad ({} points)\n",
               first.omega_rad_s / (2 * std::numbers::pi), first.theta_amplitude_rad,
               last.omega_rad_s / (2 * std::numbers::pi), last.theta_amplitude_rad, summary.points.size());
    fmt::print("wrote {0}.csv and {0}.json\n", request.output);
  }
  // The partial backbone is written; the run still failed to converge.
  if (!outcome.Complete())
    throw NumericalError("the backbone stopped early (" + summary.message +
                             "); try a smaller --max-theta-rad or fewer harmonics");
}

BEAMID_REGISTER_COMMAND("backbone", [](CLI::App& app, const GlobalOptions& global) {
  auto request = std::make_shared<workflow::TraceBackboneRequest>();
  auto measured = std::make_shared<workflow::MeasureBackboneRequest>();
  CLI::App* sub = app.add_subcommand(
      "backbone",
      "Backbone of a model: resonance frequency against amplitude of θ = y'(L) and of each sensor;\n"
      "or, with --measured, the measured backbone and damping against amplitude of a stepped-sine test.\n"
      "Example: beamid backbone examples/paper_setup/model.json --max-theta-rad 0.02 -o out/backbone\n"
      "Example: beamid backbone --measured out/base --channel acc2 --result out/result.json -o out/measured");
  sub->add_option("model", request->model_file, "Model file (JSON, see docs/model-file.md)");
  sub->add_option("--measured", measured->inputs,
                  "Measured input: a campaign folder, a phasor file of beamid extract, or first-harmonic tables "
                  "(CSV, or .mat / HDF5 files of one vector per column) or universal files of spectra / frequency "
                  "responses (one per level, docs/phasor-table.md, docs/uff58.md)");
  sub->add_option("--channel", measured->channel,
                  "With --measured: the response channel of a campaign or phasor file (default: the first sensor not "
                  "ignored); of a campaign, the other sensors' problems only warn");
  sub->add_flag("--skip-bad-steps", measured->skip_bad_steps,
                "With --measured CAMPAIGN: leave out (and list) the steps whose recordings hold errors; without it "
                "the run stops with the list");
  sub->add_option("--lines-before-header", measured->table.layout.lines_before_header,
                  "With --measured tables: the lines above the header line, skipped whatever they hold (an export's "
                  "metadata block without '#')")
      ->check(CLI::Range(0, 10000));
  sub->add_flag("--units-row", measured->table.layout.units_row,
                "With --measured tables: the line under the header gives each column's unit");
  auto columns = std::make_shared<std::vector<std::string>>();
  sub->add_option("--column", *columns,
                  "With --measured tables, repeatable: ROLE=COLUMN, a column named by the export's own header text or "
                  "by its number from 1, for ROLE frequency, excitation, response or phase "
                  "(--column 'frequency=X-Data [Hz]')");
  sub->add_option("--uff", measured->uff_folder,
                  "With --measured: also write each level into this folder as <level>.uff, its force spectrum and "
                  "frequency response (UFF 58, for a structural-dynamics tool; docs/uff58.md)")
      ->check(NonEmptyPath());
  sub->add_option("--result", measured->result_file, "With --measured: overlay this identified model's backbone")
      ->check(NonEmptyPath());
  sub->add_option("--position-m", measured->position_m, "With --measured tables and --result: the sensor's position [m]")
      ->check(FiniteRange(0.0, 100.0));
  sub->add_flag("--keep-flagged-levels", measured->keep_flagged_levels,
                "With --measured: keep flagged levels (a jump, damping not positive, peak outside the band, "
                "regeneration beyond the noise) in the cross-level fit and the damping trend; by default they are left "
                "out (the flags are shown either way)");
  // θ is the slope at the support: 1 rad (57°) is far beyond any beam.
  sub->add_option("--min-theta-rad", request->min_theta_rad, "Smallest θ amplitude [rad]")
      ->check(FiniteRange(1e-12, 1.0))
      ->capture_default_str();
  sub->add_option("--max-theta-rad", request->max_theta_rad, "Largest θ amplitude [rad]")
      ->check(FiniteRange(1e-12, 1.0))
      ->capture_default_str();
  sub->add_option("--points", request->points, "Number of amplitudes (2 … 10000)")
      ->check(CLI::Range(2, 10000))
      ->capture_default_str();
  sub->add_option("-H,--harmonics", request->harmonics, "Harmonics kept in the balance")
      ->check(CLI::Range(1, 50))
      ->capture_default_str();
  sub->add_option("-o,--output", request->output, "Output prefix: writes PREFIX.csv and PREFIX.json")
      ->capture_default_str();
  sub->callback([request, measured, columns, &global] {
    if (!measured->inputs.empty()) {
      measured->table.layout.declared_in = "the command line (--lines-before-header, --units-row)";
      for (const auto& assignment : *columns) measured->table.columns.Assign(assignment);
      if (!request->model_file.empty())
        throw std::invalid_argument("backbone: give a model file or --measured, not both");
      measured->output = request->output;
      RunMeasuredBackbone(*measured, global);
      return;
    }
    if (request->model_file.empty())
      throw std::invalid_argument("backbone: give a model file, or --measured INPUT for a test's backbone");
    if (measured->keep_flagged_levels)
      throw std::invalid_argument("backbone: --keep-flagged-levels applies to --measured only (a model has no levels)");
    if (measured->skip_bad_steps)
      throw std::invalid_argument("backbone: --skip-bad-steps applies to --measured CAMPAIGN only (a model has no "
                                  "recordings)");
    if (!measured->channel.empty())
      throw std::invalid_argument("backbone: --channel applies to --measured only; a model's backbone is that of "
                                  "every sensor");
    if (!measured->uff_folder.empty())
      throw std::invalid_argument("backbone: --uff applies to --measured only (a model has no measured levels)");
    if (measured->table.layout.lines_before_header > 0 || measured->table.layout.units_row || !columns->empty())
      throw std::invalid_argument("backbone: --lines-before-header, --units-row and --column apply to --measured "
                                  "tables only (a model has no tables)");
    RunBackbone(*request, global);
  });
});

}  // namespace
}  // namespace beamid::cli
