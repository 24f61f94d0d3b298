#include "solver/workflow/trace_response_curves.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <utility>

#include <fmt/core.h>
#include <fmt/format.h>

#include "hb/continuation.h"
#include "hb/errors.h"
#include "hb/model_file.h"
#include "hb/option_checks.h"
#include "solver/workflow/output_file.h"
#include "solver/workflow/output_paths.h"

namespace beamid::workflow {
namespace {

// The band's top may reach this multiple of the first natural frequency.
constexpr double kMaxBandOverFirstMode = 10.0;

}  // namespace

void FrcRequest::Validate() const {
  using option_checks::RequireInRange;
  // The checks the command line makes as it parses, for a caller without it.
  for (const double force_N : force_levels_N) RequireInRange("--force-N", force_N, 1e-9, 1e6);
  if (from_hz != 0.0) RequireInRange("--from-hz", from_hz, 1e-3, 1e7);
  if (to_hz != 0.0) RequireInRange("--to-hz", to_hz, 1e-3, 1e7);
  RequireInRange("-H (harmonics)", harmonics, 1, option_checks::kMaxHarmonics);
  RequireInRange("--max-points", max_points, 2, 100000);
  OutputPaths().Input(model_file).OutputPrefix("-o", output, {".csv", ".json"}).Check();
}

FrcOutcome TraceResponseCurves(const FrcRequest& options, const RunObserver& observer,
                               const FrcLevelCallback& on_level) {
  options.Validate();
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
  FrcOutcome out{.output = options.output};
  hb::FrcFile& file = out.file;
  file.model = model.name;
  file.harmonics = options.harmonics;
  file.first_natural_frequency_hz = f1_hz;
  for (const auto& s : model.sensors) {
    positions.push_back(s.position_m);
    file.sensors.push_back({.channel = s.channel, .position_m = s.position_m});
  }

  std::string& incomplete = out.incomplete;
  for (std::size_t level = 0; level < options.force_levels_N.size(); ++level) {
    const double force_N = options.force_levels_N[level];
    Eigen::VectorXcd force = Eigen::VectorXcd::Zero(2);
    force[1] = force_N;
    ObservedTask progress(observer,
                          fmt::format("frc: level {}/{} ({} N)", level + 1, options.force_levels_N.size(), force_N));
    const auto summary = hb::TraceFrequencyResponse(
        balance, force,
        {.omega_start_rad_s = 2 * std::numbers::pi * from_hz, .omega_end_rad_s = 2 * std::numbers::pi * to_hz,
         .max_points = options.max_points},
        [&](double fraction) { progress.Update(fraction); });
    progress.End();
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
    FrcLevelSummary& done = out.levels.emplace_back(FrcLevelSummary{.force_N = force_N,
                                                                   .num_points = summary.points.size(),
                                                                   .turning_points = summary.num_turning_points,
                                                                   .complete = summary.reached_end});
    for (const auto& p : summary.points)
      if (std::abs(p.theta_rad[1]) > done.peak_theta_rad) {
        done.peak_theta_rad = std::abs(p.theta_rad[1]);
        done.peak_frequency_hz = p.omega_rad_s / (2 * std::numbers::pi);
      }
    if (on_level) on_level(done);
  }
  WriteTextFile(options.output + ".csv", hb::FrcFileToCsv(file));
  WriteTextFile(options.output + ".json", hb::FrcFileToJson(file));
  return out;
}

}  // namespace beamid::workflow
