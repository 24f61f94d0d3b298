// beamid frc: frequency response curves of a model by harmonic balance and
// pseudo-arclength continuation, at one or more force levels.
#include <cmath>
#include <numbers>
#include <sstream>

#include <fmt/core.h>
#include <fmt/format.h>

#include "hb/version.h"
#include "hb/errors.h"
#include "hb/continuation.h"
#include "hb/model_file.h"
#include "solver/cli/cli_output.h"
#include "solver/cli/command_registry.h"

namespace beamid::cli {
namespace {

struct FrcOptions {
  std::string model_file;
  std::vector<double> force_levels_N = {0.5, 1.0, 2.0};
  double from_hz = 0.0;  // 0 = 0.9 × the first natural frequency
  double to_hz = 0.0;    // 0 = 1.1 × the first natural frequency
  int harmonics = 7;
  int max_points = 3000;
  std::string output = "frc";
};

void RunFrc(const FrcOptions& options, const GlobalOptions& global) {
  const hb::ModelFile model = hb::ReadModelFile(options.model_file);
  if (options.harmonics < 1 || options.harmonics > 50)
    throw std::invalid_argument("--harmonics must lie between 1 and 50");
  for (double f : options.force_levels_N)
    if (!(f > 0.0)) throw std::invalid_argument("--force-N: every force amplitude must be positive");
  const auto law = model.MakeSupportLaw();
  hb::LinearBeamModel linear_model{.beam = model.beam, .attachments = model.attachments,
                                   .support_stiffness_Nm_rad = law->InitialStiffness_Nm_rad()};
  const double f1_hz =
      hb::LinearBeam(linear_model, model.force_position_m).NaturalFrequencies_rad_s(1)[0] / (2 * std::numbers::pi);
  const double from_hz = options.from_hz > 0 ? options.from_hz : 0.9 * f1_hz;
  const double to_hz = options.to_hz > 0 ? options.to_hz : 1.1 * f1_hz;
  if (from_hz == to_hz) throw std::invalid_argument("--from-hz and --to-hz must differ");

  linear_model.support_stiffness_Nm_rad = 0.0;  // the law carries the support
  const hb::LinearBeam beam(linear_model, model.force_position_m,
                            {.max_frequency_hz = 1.5 * (options.harmonics + 1) * std::max(from_hz, to_hz)});
  const hb::HarmonicBalance balance(beam, *law, {.num_harmonics = options.harmonics});
  std::vector<double> positions;
  std::vector<std::string> names;
  for (const auto& s : model.sensors) {
    positions.push_back(s.position_m);
    names.push_back(s.channel);
  }

  std::ostringstream csv;
  csv << "force_N,frequency_Hz,stable";
  for (int k = 1; k <= options.harmonics; ++k) csv << fmt::format(",theta_h{0}_amp_rad,theta_h{0}_phase_rad", k);
  for (const auto& name : names)
    for (int k = 1; k <= options.harmonics; ++k)
      csv << fmt::format(",{0}_h{1}_disp_amp_m,{0}_h{1}_disp_phase_rad,{0}_h{1}_acc_amp_m_s2,{0}_h{1}_acc_phase_rad",
                         name, k);
  csv << '\n';
  nlohmann::json curves = nlohmann::json::array();
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
    nlohmann::json points = nlohmann::json::array();
    for (const auto& p : summary.points) {
      const hb::HarmonicBalanceSolution solution{.omega_rad_s = p.omega_rad_s, .theta_rad = p.theta_rad};
      const Eigen::MatrixXcd y = balance.Displacements(solution, force, positions);
      csv << fmt::format("{},{:.9g},{:d}", force_N, p.omega_rad_s / (2 * std::numbers::pi), p.stable);
      for (int k = 1; k <= options.harmonics; ++k)
        csv << fmt::format(",{:.9g},{:.9g}", std::abs(p.theta_rad[k]), std::arg(p.theta_rad[k]));
      nlohmann::json at_positions = nlohmann::json::object();
      for (std::size_t i = 0; i < positions.size(); ++i) {
        Eigen::VectorXcd acceleration(options.harmonics + 1);
        for (int k = 0; k <= options.harmonics; ++k) {
          const double kw = k * p.omega_rad_s;
          acceleration[k] = -kw * kw * y(i, k);
          if (k > 0)
            csv << fmt::format(",{:.9g},{:.9g},{:.9g},{:.9g}", std::abs(y(i, k)), std::arg(y(i, k)),
                               std::abs(acceleration[k]), std::arg(acceleration[k]));
        }
        at_positions[names[i]] = {{"position_m", positions[i]},
                                  {"displacement_m", PhasorsToJson(y.row(i).transpose())},
                                  {"acceleration_m_s2", PhasorsToJson(acceleration)}};
      }
      csv << '\n';
      points.push_back({{"frequency_Hz", p.omega_rad_s / (2 * std::numbers::pi)},
                        {"stable", p.stable},
                        {"theta_rad", PhasorsToJson(p.theta_rad)},
                        {"sensors", at_positions}});
    }
    curves.push_back({{"force_N", force_N},
                      {"turning_points", summary.num_turning_points},
                      {"complete", summary.reached_end},
                      {"points", points}});
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
  nlohmann::json out = {{"command", "frc"},
                        {"beamid_version", kVersion},
                        {"model", model.name},
                        {"harmonics", options.harmonics},
                        {"phasor_convention", "x(t) = X0 + sum_k Re(X_k exp(i k w t)), peak amplitudes, SI"},
                        {"first_natural_frequency_Hz", f1_hz},
                        {"curves", curves}};
  WriteTextFile(options.output + ".csv", csv.str());
  WriteTextFile(options.output + ".json", out.dump(1));
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
  sub->add_option("model", options->model_file, "Model file (JSON, see README 'Model files')")->required();
  sub->add_option("--force-N", options->force_levels_N, "Force amplitudes [N], comma-separated")->delimiter(',');
  sub->add_option("--from-hz", options->from_hz, "Start frequency [Hz] (default 0.9 × first natural frequency)");
  sub->add_option("--to-hz", options->to_hz, "End frequency [Hz] (default 1.1 × first natural frequency)");
  sub->add_option("-H,--harmonics", options->harmonics, "Harmonics kept in the balance")->capture_default_str();
  sub->add_option("--max-points", options->max_points, "Most continuation points per curve")->capture_default_str();
  sub->add_option("-o,--output", options->output, "Output prefix: writes PREFIX.csv and PREFIX.json")
      ->capture_default_str();
  sub->callback([options, &global] { RunFrc(*options, global); });
});

}  // namespace
}  // namespace beamid::cli
