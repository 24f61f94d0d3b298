// beamid backbone: the model's backbone — resonance frequency against
// amplitude — by exact harmonic balance (phase resonance), with the paper's
// corrected multiple-scales backbone beside it for a polynomial support; or,
// with --measured, the measured backbone of a test (measured_backbone_command.h).
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>

#include <fmt/core.h>

#include "hb/errors.h"
#include "hb/backbone.h"
#include "hb/backbone_file.h"
#include "hb/model_file.h"
#include "hb/multiple_scales.h"
#include "solver/cli/cli_output.h"
#include "solver/workflow/output_file.h"
#include "solver/cli/command_registry.h"
#include "solver/workflow/output_paths.h"
#include "solver/cli/measured_backbone_command.h"

namespace beamid::cli {
namespace {

struct BackboneCommandOptions {
  std::string model_file;
  double min_theta_rad = 1e-5;
  double max_theta_rad = 2e-2;
  int points = 200;
  int harmonics = 7;
  std::string output = "backbone";
};

void RunBackbone(const BackboneCommandOptions& options, const GlobalOptions& global) {
  workflow::OutputPaths().Input(options.model_file).OutputPrefix("-o", options.output, {".csv", ".json"}).Check();
  if (!(options.min_theta_rad < options.max_theta_rad))
    throw InputError(fmt::format("--min-theta-rad {} must lie below --max-theta-rad {}", options.min_theta_rad,
                                 options.max_theta_rad));
  const hb::ModelFile model = hb::ReadModelFile(options.model_file);
  const auto law = model.MakeSupportLaw();
  const hb::LinearBeamModel linear_model{.beam = model.beam, .attachments = model.attachments};
  // Segments sized for harmonic H of a resonance that may rise by half.
  const double f_guess_hz =
      hb::LinearBeam({.beam = model.beam, .attachments = model.attachments,
                      .support_stiffness_Nm_rad = law->InitialStiffness_Nm_rad()},
                     model.force_position_m)
          .NaturalFrequencies_rad_s(1)[0] /
      (2 * std::numbers::pi);
  const hb::LinearBeam beam(linear_model, model.force_position_m,
                            {.max_frequency_hz = 1.5 * (options.harmonics + 1) * 1.5 * f_guess_hz});
  const hb::HarmonicBalance balance(beam, *law, {.num_harmonics = options.harmonics});
  Progress progress("backbone", global);
  const auto summary = hb::TraceBackbone(
      balance,
      {.min_theta_amplitude_rad = options.min_theta_rad, .max_theta_amplitude_rad = options.max_theta_rad,
       .num_points = options.points},
      {}, [&](double fraction) { progress.Update(fraction); });
  progress.Done();

  // The multiple-scales backbone models a plain beam with a polynomial law.
  std::optional<hb::MultipleScalesModel> ms;
  if (!model.jenkins && model.attachments.point_masses.empty() &&
      !std::isfinite(model.attachments.clamp_rotational_stiffness_Nm_rad) &&
      !std::isfinite(model.attachments.support_translational_stiffness_N_m))
    ms.emplace(model.beam, model.polynomial, model.force_position_m);

  std::vector<double> positions;
  hb::BackboneFile file;
  file.model = model.name;
  file.harmonics = options.harmonics;
  file.complete = summary.complete;
  for (const auto& s : model.sensors) {
    positions.push_back(s.position_m);
    file.sensors.push_back({.channel = s.channel, .position_m = s.position_m});
  }
  for (const auto& p : summary.points) {
    Eigen::VectorXcd force = Eigen::VectorXcd::Zero(2);
    force[1] = p.force_amplitude_N;
    const hb::HarmonicBalanceSolution solution{.omega_rad_s = p.omega_rad_s, .theta_rad = p.theta_rad};
    const Eigen::MatrixXcd y = balance.Displacements(solution, force, positions);
    double ms_hz = std::numeric_limits<double>::quiet_NaN();  // none
    if (ms) {
      try {
        ms_hz = ms->Backbone_rad_s(p.theta_amplitude_rad / std::abs(ms->SupportSlope_per_m())) /
                (2 * std::numbers::pi);
      } catch (const NumericalError&) {
        // beyond the perturbation model's range: no value
      }
    }
    hb::BackboneFilePoint point{.theta_amplitude_rad = p.theta_amplitude_rad,
                                .frequency_hz = p.omega_rad_s / (2 * std::numbers::pi),
                                .force_N = p.force_amplitude_N,
                                .multiple_scales_frequency_hz = ms_hz,
                                .theta_rad = {p.theta_rad.begin(), p.theta_rad.end()},
                                .sensors = {}};
    for (std::size_t i = 0; i < positions.size(); ++i)
      point.sensors.push_back({.displacement_m = {y.row(i).begin(), y.row(i).end()}});
    file.points.push_back(std::move(point));
  }
  workflow::WriteTextFile(options.output + ".csv", hb::BackboneFileToCsv(file));
  workflow::WriteTextFile(options.output + ".json", hb::BackboneFileToJson(file));
  if (!global.quiet && !summary.points.empty()) {
    const auto& first = summary.points.front();
    const auto& last = summary.points.back();
    fmt::print("  backbone: {:.3f} Hz at |θ1| = {:.1e} rad → {:.3f} Hz at {:.1e} rad ({} points)\n",
               first.omega_rad_s / (2 * std::numbers::pi), first.theta_amplitude_rad,
               last.omega_rad_s / (2 * std::numbers::pi), last.theta_amplitude_rad, summary.points.size());
    fmt::print("wrote {0}.csv and {0}.json\n", options.output);
  }
  // The partial backbone is written; the run still failed to converge.
  if (!summary.complete)
    throw NumericalError("the backbone stopped early (" + summary.message +
                             "); try a smaller --max-theta-rad or fewer harmonics");
}

BEAMID_REGISTER_COMMAND("backbone", [](CLI::App& app, const GlobalOptions& global) {
  auto options = std::make_shared<BackboneCommandOptions>();
  auto measured = std::make_shared<MeasuredBackboneCommandOptions>();
  CLI::App* sub = app.add_subcommand(
      "backbone",
      "Backbone of a model: resonance frequency against amplitude of θ = y'(L) and of each sensor;\n"
      "or, with --measured, the measured backbone and damping against amplitude of a stepped-sine test.\n"
      "Example: beamid backbone examples/paper_setup/model.json --max-theta-rad 0.02 -o out/backbone\n"
      "Example: beamid backbone --measured out/base --channel acc2 --result out/result.json -o out/measured");
  sub->add_option("model", options->model_file, "Model file (JSON, see docs/model-file.md)");
  sub->add_option("--measured", measured->inputs,
                  "Measured input: a campaign folder, a phasor file of beamid extract, or first-harmonic CSV tables "
                  "(one per level, docs/phasor-table.md)");
  sub->add_option("--channel", measured->channel, "With --measured: the response channel of a campaign (default: first)");
  sub->add_option("--result", measured->result_file, "With --measured: overlay this identified model's backbone")
      ->check(NonEmptyPath());
  sub->add_option("--position-m", measured->position_m, "With --measured tables and --result: the sensor's position [m]")
      ->check(FiniteRange(0.0, 100.0));
  sub->add_flag("--keep-flagged-levels", measured->keep_flagged_levels,
                "With --measured: keep flagged levels (a jump, damping not positive, peak outside the band, "
                "regeneration beyond the noise) in the cross-level fit and the damping trend; by default they are left "
                "out (the flags are shown either way)");
  // θ is the slope at the support: 1 rad (57°) is far beyond any beam.
  sub->add_option("--min-theta-rad", options->min_theta_rad, "Smallest θ amplitude [rad]")
      ->check(FiniteRange(1e-12, 1.0))
      ->capture_default_str();
  sub->add_option("--max-theta-rad", options->max_theta_rad, "Largest θ amplitude [rad]")
      ->check(FiniteRange(1e-12, 1.0))
      ->capture_default_str();
  sub->add_option("--points", options->points, "Number of amplitudes (2 … 10000)")
      ->check(CLI::Range(2, 10000))
      ->capture_default_str();
  sub->add_option("-H,--harmonics", options->harmonics, "Harmonics kept in the balance")
      ->check(CLI::Range(1, 50))
      ->capture_default_str();
  sub->add_option("-o,--output", options->output, "Output prefix: writes PREFIX.csv and PREFIX.json")
      ->capture_default_str();
  sub->callback([options, measured, &global] {
    if (!measured->inputs.empty()) {
      if (!options->model_file.empty())
        throw std::invalid_argument("backbone: give a model file or --measured, not both");
      measured->output = options->output;
      RunMeasuredBackbone(*measured, global);
      return;
    }
    if (options->model_file.empty())
      throw std::invalid_argument("backbone: give a model file, or --measured INPUT for a test's backbone");
    if (measured->keep_flagged_levels)
      throw std::invalid_argument("backbone: --keep-flagged-levels applies to --measured only (a model has no levels)");
    RunBackbone(*options, global);
  });
});

}  // namespace
}  // namespace beamid::cli
