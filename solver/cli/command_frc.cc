// beamid frc: frequency response curves of a model by harmonic balance and
// pseudo-arclength continuation, at one or more force levels. The work is
// workflow::TraceResponseCurves; this prints each level and maps a curve
// that stopped early to exit 3 (after writing the curves).
#include <string>

#include <fmt/core.h>

#include "hb/errors.h"
#include "solver/cli/cli_output.h"
#include "solver/cli/command_registry.h"
#include "solver/workflow/trace_response_curves.h"

namespace beamid::cli {
namespace {

void RunFrc(const workflow::FrcRequest& request, const GlobalOptions& global) {
  const auto print_level = [&](const workflow::FrcLevelSummary& level) {
    if (!global.quiet)
      fmt::print("  {:6.3f} N: {} points, {} turning points, peak |θ1| = {:.3e} rad at {:.3f} Hz\n", level.force_N,
                 level.num_points, level.turning_points, level.peak_theta_rad, level.peak_frequency_hz);
  };
  const workflow::FrcOutcome outcome = workflow::TraceResponseCurves(request, CliObserver(global), print_level);
  const std::string& incomplete = outcome.Incomplete();
  if (!global.quiet) fmt::print("wrote {0}.csv and {0}.json\n", request.output);
  // The partial curves are written; the run still failed to converge.
  if (!incomplete.empty())
    throw NumericalError(incomplete + "; try a smaller range, more --max-points or fewer harmonics");
}

BEAMID_REGISTER_COMMAND("frc", [](CLI::App& app, const GlobalOptions& global) {
  auto request = std::make_shared<workflow::FrcRequest>();
  CLI::App* sub = app.add_subcommand(
      "frc",
      "Frequency response curves by harmonic balance and continuation (stable and unstable branches).\n"
      "Example: beamid frc examples/paper_setup/model.json --force-N 0.5,1,2 --from-hz 50 --to-hz 58 -o out/frc");
  sub->add_option("model", request->model_file, "Model file (JSON, see docs/model-file.md)")->required();
  sub->add_option("--force-N", request->force_levels_N, "Force amplitudes [N], comma-separated")
      ->delimiter(',')
      ->check(FiniteRange(1e-9, 1e6));
  sub->add_option("--from-hz", request->from_hz,
                  "Start frequency [Hz] (default 0.9 × first natural frequency; at most 10 × it)")
      ->check(FiniteRange(1e-3, 1e7));
  sub->add_option("--to-hz", request->to_hz, "End frequency [Hz] (default 1.1 × first natural frequency; at most 10 × it)")
      ->check(FiniteRange(1e-3, 1e7));
  sub->add_option("-H,--harmonics", request->harmonics, "Harmonics kept in the balance")
      ->check(CLI::Range(1, 50))
      ->capture_default_str();
  sub->add_option("--max-points", request->max_points, "Most continuation points per curve")
      ->check(CLI::Range(2, 100000))
      ->capture_default_str();
  sub->add_option("-o,--output", request->output, "Output prefix: writes PREFIX.csv and PREFIX.json")
      ->capture_default_str();
  sub->callback([request, &global] { RunFrc(*request, global); });
});

}  // namespace
}  // namespace beamid::cli
