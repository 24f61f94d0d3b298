#include "solver/workflow/trace_model_backbone.h"

#include <cmath>
#include <limits>
#include <numbers>
#include <optional>

#include <fmt/core.h>

#include "hb/errors.h"
#include "hb/model_file.h"
#include "hb/multiple_scales.h"
#include "hb/option_checks.h"
#include "solver/workflow/output_file.h"
#include "solver/workflow/output_paths.h"

namespace beamid::workflow {

void TraceBackboneRequest::Validate() const {
  using option_checks::RequireInRange;
  if (model_file.empty())
    throw InputError("model file: none given. Fix: give the model's file (JSON, docs/model-file.md)");
  // The checks the command line makes as it parses, for a caller without it.
  // θ is the slope at the support: 1 rad (57°) is far beyond any beam.
  RequireInRange("--min-theta-rad", min_theta_rad, 1e-12, 1.0);
  RequireInRange("--max-theta-rad", max_theta_rad, 1e-12, 1.0);
  RequireInRange("--points", points, 2, 10000);
  RequireInRange("-H (harmonics)", harmonics, 1, option_checks::kMaxHarmonics);
  OutputPaths().Input(model_file).OutputPrefix("-o", output, {".csv", ".json"}).Check();
  if (!(min_theta_rad < max_theta_rad))
    throw InputError(fmt::format("--min-theta-rad {} must lie below --max-theta-rad {}", min_theta_rad,
                                 max_theta_rad));
}

TraceBackboneOutcome TraceModelBackbone(const TraceBackboneRequest& options, const RunObserver& observer) {
  options.Validate();
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
  TraceBackboneOutcome out{.output = options.output};
  ObservedTask progress(observer, "backbone");
  out.summary = hb::TraceBackbone(
      balance,
      {.min_theta_amplitude_rad = options.min_theta_rad, .max_theta_amplitude_rad = options.max_theta_rad,
       .num_points = options.points},
      {}, [&](double fraction) { progress.Update(fraction); });
  progress.End();
  const hb::BackboneSummary& summary = out.summary;

  // The multiple-scales backbone models a plain beam with a polynomial law.
  std::optional<hb::MultipleScalesModel> ms;
  if (!model.jenkins && model.attachments.point_masses.empty() &&
      !std::isfinite(model.attachments.clamp_rotational_stiffness_Nm_rad) &&
      !std::isfinite(model.attachments.support_translational_stiffness_N_m))
    ms.emplace(model.beam, model.polynomial, model.force_position_m);

  std::vector<double> positions;
  hb::BackboneFile& file = out.file;
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
  WriteTextFile(options.output + ".csv", hb::BackboneFileToCsv(file));
  WriteTextFile(options.output + ".json", hb::BackboneFileToJson(file));
  return out;
}

}  // namespace beamid::workflow
