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

struct FrcOptions {
  std::string model_file;
  std::vector<double> force_levels_N = {0.5, 1.0, 2.0};
  // 0: not given (the options refuse 0), 0.9 and 1.1 × the first natural frequency.
  double from_hz = 0.0;
  double to_hz = 0.0;
  int harmonics = 7;
  int max_points = 3000;
  std::string output = "frc";
};

void RunFrc(const FrcOptions& options, const GlobalOptions& global) {
  const auto print_level = [&](const workflow::FrcLevelSummary& level) {
    if (!global.quiet)
      fmt::print("  {:6.3f} N: {} points, {} turning points, peak |θ1| = {:.3e} rad at {:.3f} Hz\n", level.force_N,
                 level.num_points, level.turning_points, level.peak_theta_rad, level.peak_frequency_hz);
  };
  const workflow::FrcOutcome outcome = workflow::TraceResponseCurves({.model_file = options.model_file,
                                                                         .force_levels_N = options.force_levels_N,
                                                                         .from_hz = options.from_hz,
                                                                         .to_hz = options.to_hz,
                                                                         .harmonics = options.harmonics,
                                                                         .max_points = options.max_points,
                                                                         .output = options.output},
                                                                        CliObserver(global), print_level);
  const std::string& incomplete = outcome.Incomplete();
  if (!global.quiet) fmt::print("wrote {0}.csv and {0}.json\n", options.output);
  // The partial curves are written; the run still failed to converge.
  if (!incomplete.empty())
    throw NumericalError(incomplete + "; try a smaller range, more --max-points or fewer harmonics");
}

BEAMID_REGISTER_COMMAND("frc", [](CLI::App& app, const GlobalOptions& global) {
  auto options = std::make_shared<FrcOptions>();
  CLI::App* sub = app.add_subcommand(
      "frc",
      "Frequency response curves by harmonic balance and continuation (stable and unstable branches).\n"
      "Example: beamid frc examples/paper_setup/model.json --force-N 0.5,1,2 --from-hz 50 --to-hz 58 -o out/frc");
  sub->add_option("model", options->model_file, "Model file (JSON, see docs/model-file.md)")->required();
  sub->add_option("--force-N", options->force_levels_N, "Force amplitudes [N], comma-separated")
      ->delimiter(',')
      ->check(FiniteRange(1e-9, 1e6));
  sub->add_option("--from-hz", options->from_hz,
                  "Start frequency [Hz] (default 0.9 × first natural frequency; at most 10 × it)")
      ->check(FiniteRange(1e-3, 1e7));
  sub->add_option("--to-hz", options->to_hz, "End frequency [Hz] (default 1.1 × first natural frequency; at most 10 × it)")
      ->check(FiniteRange(1e-3, 1e7));
  sub->add_option("-H,--harmonics", options->harmonics, "Harmonics kept in the balance")
      ->check(CLI::Range(1, 50))
      ->capture_default_str();
  sub->add_option("--max-points", options->max_points, "Most continuation points per curve")
      ->check(CLI::Range(2, 100000))
      ->capture_default_str();
  sub->add_option("-o,--output", options->output, "Output prefix: writes PREFIX.csv and PREFIX.json")
      ->capture_default_str();
  sub->callback([options, &global] { RunFrc(*options, global); });
});

}  // namespace
}  // namespace beamid::cli
