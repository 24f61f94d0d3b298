// beamid frc: frequency response curves of a model by harmonic balance and
// pseudo-arclength continuation, at one or more force levels.
#include <cmath>
#include <numbers>
#include <utility>

#include <fmt/core.h>
#include <fmt/format.h>

#include "hb/errors.h"
#include "hb/continuation.h"
#include "hb/frc_file.h"
#include "hb/model_file.h"
#include "solver/cli/cli_output.h"
#include "solver/workflow/output_file.h"
#include "solver/cli/command_registry.h"
#include "solver/workflow/output_paths.h"

namespace beamid::cli {
namespace {

// The band's top may reach this multiple of the first natural frequency.
constexpr double kMaxBandOverFirstMode = 10.0;

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
  workflow::OutputPaths().Input(options.model_file).OutputPrefix("-o", options.output, {".csv", ".json"}).Check();
  const hb::ModelFile model = hb::ReadModelFile(options.model_file);
  const auto law = model.MakeSupportLaw();
  hb::LinearBeamModel linear_model{.beam = model.beam, .attachments = model.attachments,
                                   .support_stiffness_Nm_rad = law->InitialStiffness_Nm_rad()};
  const double f1_hz =
      hb::LinearBeam(linear_model, model.force_position_m).NaturalFrequencies_rad_s(1)[0] / (2 * std::numbers::pi);
  const double from_hz = options.from_hz > 0 ? options.from_hz : 0.9 * f1_hz;
  const double to_hz = options.to_hz > 0 ? options.to_hz : 1.1 * f1_hz;
  if (from_hz == to_hz) throw InputError("--from-hz and --to-hz must differ");
  // The balance holds every mode up to (H + 1) × the band's top: a band far
  // above the first mode would take hours (1 MHz: a minute per curve).
  const double most_hz = kMaxBandOverFirstMode * f1_hz;
  for (const auto& [option, hz] : {std::pair{"--from-hz", from_hz}, std::pair{"--to-hz", to_hz}})
    if (hz > most_hz)
      throw InputError(fmt::format("{} {} Hz lies beyond {} × the model's first natural frequency ({:.6g} Hz): "
                                   "give a band of at most {:.6g} Hz",
                                   option, hz, kMaxBandOverFirstMode, f1_hz, most_hz));

  linear_model.support_stiffness_Nm_rad = 0.0;  // the law carries the support
  const hb::LinearBeam beam(linear_model, model.force_position_m,
                            {.max_frequency_hz = 1.5 * (options.harmonics + 1) * std::max(from_hz, to_hz)});
  const hb::HarmonicBalance balance(beam, *law, {.num_harmonics = options.harmonics});
  std::vector<double> positions;
  hb::FrcFile file;
  file.model = model.name;
  file.harmonics = options.harmonics;
  file.first_natural_frequency_hz = f1_hz;
  for (const auto& s : model.sensors) {
    positions.push_back(s.position_m);
    file.sensors.push_back({.channel = s.channel, .position_m = s.position_m});
  }

  std::string incomplete;
  for (std::size_t level = 0; level < options.force_levels_N.size(); ++level) {
    const double force_N = options.force_levels_N[level];
    Eigen::VectorXcd force = Eigen::VectorXcd::Zero(2);
    force[1] = force_N;
    Progress progress(fmt::format("frc: level {}/{} ({} N)", level + 1, options.force_levels_N.size(), force_N),
                      global);
    const auto summary = hb::TraceFrequencyResponse(
        balance, force,
        {.omega_start_rad_s = 2 * std::numbers::pi * from_hz, .omega_end_rad_s = 2 * std::numbers::pi * to_hz,
         .max_points = options.max_points},
        [&](double fraction) { progress.Update(fraction); });
    progress.Done();
    if (!summary.reached_end)
      incomplete += fmt::format("{}the curve at {} N stopped early ({})", incomplete.empty() ? "" : "; ", force_N,
                                summary.message);
    hb::FrcCurve curve{.force_N = force_N,
                       .turning_points = summary.num_turning_points,
                       .complete = summary.reached_end,
                       .points = {}};
    for (const auto& p : summary.points) {
      const hb::HarmonicBalanceSolution solution{.omega_rad_s = p.omega_rad_s, .theta_rad = p.theta_rad};
      const Eigen::MatrixXcd y = balance.Displacements(solution, force, positions);
      hb::FrcPoint point{.frequency_hz = p.omega_rad_s / (2 * std::numbers::pi),
                         .stable = p.stable,
                         .theta_rad = {p.theta_rad.begin(), p.theta_rad.end()},
                         .sensors = {}};
      for (std::size_t i = 0; i < positions.size(); ++i) {
        hb::FrcSensorPhasors at_sensor;
        for (int k = 0; k <= options.harmonics; ++k) {
          const double kw = k * p.omega_rad_s;
          at_sensor.displacement_m.push_back(y(i, k));
          at_sensor.acceleration_m_s2.push_back(-kw * kw * y(i, k));
        }
        point.sensors.push_back(std::move(at_sensor));
      }
      curve.points.push_back(std::move(point));
    }
    file.curves.push_back(std::move(curve));
    if (!global.quiet) {
      double peak = 0, f_peak = 0;
      for (const auto& p : summary.points)
        if (std::abs(p.theta_rad[1]) > peak) {
          peak = std::abs(p.theta_rad[1]);
          f_peak = p.omega_rad_s / (2 * std::numbers::pi);
        }
      fmt::print("  {:6.3f} N: {} points, {} turning points, peak |θ1| = {:.3e} rad at {:.3f} Hz\n", force_N,
                 summary.points.size(), summary.num_turning_points, peak, f_peak);
    }
  }
  workflow::WriteTextFile(options.output + ".csv", hb::FrcFileToCsv(file));
  workflow::WriteTextFile(options.output + ".json", hb::FrcFileToJson(file));
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
