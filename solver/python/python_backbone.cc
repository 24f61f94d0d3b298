// measured_backbone and model_backbone: the model-free backbone of a test
// (`beamid backbone --measured`) and a model file's backbone (`beamid
// backbone MODEL`), solver/workflow/measure_backbone.h and
// trace_model_backbone.h.
#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "hb/backbone_file.h"
#include "hb/errors.h"
#include "solver/backbone/measured_backbone.h"
#include "solver/python/module_functions.h"
#include "solver/python/python_arrays.h"
#include "solver/python/python_errors.h"
#include "solver/python/python_run.h"
#include "solver/workflow/measure_backbone.h"
#include "solver/workflow/trace_model_backbone.h"

namespace py = pybind11;
using namespace pybind11::literals;

namespace beamid::python {
namespace {

// An estimate's value and σ under the keys `name` and `std_name`; NaN when
// it was not estimated, where the CSV leaves both cells empty.
void PutEstimate(py::dict& d, const std::string& name, const std::string& std_name, const solver::Estimate& e) {
  d[py::str(name)] = e.valid ? e.value : kMissing;
  d[py::str(std_name)] = e.valid && std::isfinite(e.value) ? e.std : kMissing;
}

py::dict LevelToPython(const solver::MeasuredBackbone& measured, const solver::LevelResonance& l) {
  py::dict d("level"_a = l.label, "control"_a = workflow::LevelControlText(measured, l), "num_points"_a = l.num_points);
  PutEstimate(d, "quadrature_frequency_hz", "quadrature_frequency_std_hz", l.quadrature_frequency_hz);
  PutEstimate(d, "amplitude_m", "amplitude_std_m", l.quadrature_amplitude_m);
  PutEstimate(d, "response_amplitude", "response_amplitude_std", l.quadrature_response_amplitude);
  PutEstimate(d, "excitation_amplitude", "excitation_amplitude_std", l.quadrature_force_N);
  PutEstimate(d, "zeta_quadrature", "zeta_quadrature_std", l.quadrature_damping_ratio);
  PutEstimate(d, "zeta_local", "zeta_local_std", l.local_damping_ratio);
  PutEstimate(d, "zeta_half_power", "zeta_half_power_std", l.half_power_damping_ratio);
  PutEstimate(d, "peak_frequency_hz", "peak_frequency_std_hz", l.peak_frequency_hz);
  PutEstimate(d, "local_natural_frequency_hz", "local_natural_frequency_std_hz", l.local_natural_frequency_hz);
  d["regeneration_relative_rms"] = l.regeneration_relative_rms;
  d["in_global_fit"] = l.in_global_fit;
  py::list flags;
  for (const solver::LevelFlag& f : l.flags)
    flags.append(py::dict(py::arg("kind") = std::string(solver::LevelFlagName(f.kind)),
                          py::arg("quantity") = f.quantity, py::arg("message") = f.message));
  d["flags"] = flags;
  PutEstimate(d, "zeta", "zeta_std", l.damping_ratio);
  std::vector<double> frequency, receptance, phase;
  for (const solver::LevelFrfPoint& p : l.measured_frf) {
    frequency.push_back(p.frequency_hz);
    receptance.push_back(p.receptance_m_N);
    phase.push_back(p.phase_rad);
  }
  d["measured_frf"] = py::dict(py::arg("frequency_hz") = ToArray(frequency),
                               py::arg("receptance_m_N") = ToArray(receptance), py::arg("phase_rad") = ToArray(phase));
  return d;
}

py::dict MeasuredToPython(const workflow::MeasureBackboneOutcome& outcome) {
  const solver::MeasuredBackbone& measured = outcome.measured;
  py::dict d("kind"_a = "measured_backbone", "channel"_a = outcome.channel,
             "response_quantity"_a = measured.response_quantity,
             "excitation_quantity"_a = measured.excitation_quantity);
  // The CSV's name of excitation_amplitude ("force_N", "voltage_V", ...).
  d["excitation_column"] = solver::LabelsOf(measured.excitation_quantity).column;
  py::list levels;
  for (const auto& l : measured.levels) levels.append(LevelToPython(measured, l));
  d["levels"] = levels;
  d["fit_form"] = measured.fit.FormName();
  const solver::DampingTrend& trend = measured.damping_trend;
  d["damping_trend"] = py::dict(
      py::arg("verdict") = std::string(schema::NameOf(trend.verdict, solver::kDampingRateTrendNames)),
      py::arg("damping_ratio_verdict") = std::string(schema::NameOf(trend.damping_ratio_verdict,
                                                                    solver::kDampingRatioTrendNames)),
      py::arg("z") = trend.z, py::arg("damping_rate_z") = trend.damping_rate_z, py::arg("note") = trend.note);
  d["min_amplitude_m"] = measured.min_amplitude_m;
  d["max_amplitude_m"] = measured.max_amplitude_m;
  d["warnings"] = ToList(measured.warnings);
  return d;
}

py::dict ModelBackboneToPython(const hb::BackboneFile& file) {
  const std::size_t n = file.points.size();
  py::array_t<double> theta = NanArray(n), frequency = NanArray(n), force = NanArray(n), ms_frequency = NanArray(n);
  // A point's sensors are the file's, in its order (hb/backbone_file.h).
  std::vector<py::array_t<std::complex<double>>> sensors;
  for (std::size_t j = 0; j < file.sensors.size(); ++j)
    sensors.push_back(NanMatrix<std::complex<double>>(n, file.harmonics + 1));
  auto theta_phasors = NanMatrix<std::complex<double>>(n, file.harmonics + 1);
  const auto columns = static_cast<std::size_t>(file.harmonics) + 1;
  for (std::size_t i = 0; i < n; ++i) {
    const hb::BackboneFilePoint& p = file.points[i];
    const auto row = static_cast<py::ssize_t>(i);
    theta.mutable_at(row) = p.theta_amplitude_rad;
    frequency.mutable_at(row) = p.frequency_hz;
    force.mutable_at(row) = p.force_N;
    ms_frequency.mutable_at(row) = p.multiple_scales_frequency_hz;
    for (std::size_t k = 0; k < std::min(p.theta_rad.size(), columns); ++k)
      theta_phasors.mutable_at(row, static_cast<py::ssize_t>(k)) = p.theta_rad[k];
    for (std::size_t j = 0; j < std::min(p.sensors.size(), sensors.size()); ++j)
      for (std::size_t k = 0; k < std::min(p.sensors[j].displacement_m.size(), columns); ++k)
        sensors[j].mutable_at(row, static_cast<py::ssize_t>(k)) = p.sensors[j].displacement_m[k];
  }
  py::dict by_sensor;
  for (std::size_t j = 0; j < file.sensors.size(); ++j)
    by_sensor[py::str(file.sensors[j].channel)] =
        py::dict("position_m"_a = file.sensors[j].position_m, "displacement_m"_a = sensors[j]);
  py::dict d("kind"_a = "model_backbone", "model"_a = file.model, "harmonics"_a = file.harmonics,
             "complete"_a = file.complete, "theta_amplitude_rad"_a = theta, "frequency_hz"_a = frequency,
             "force_N"_a = force, "multiple_scales_frequency_hz"_a = ms_frequency, "theta_rad"_a = theta_phasors,
             "sensors"_a = by_sensor);
  return d;
}

// A prefix the caller gave, or one in the run's temporary folder.
std::string Prefix(PythonRun& run, const OptionalPath& output) {
  return run.OutputPath(output, "backbone");
}


}  // namespace

void AddBackboneFunctions(py::module_& module) {
  module.def(
      "measured_backbone",
      [](const std::variant<Path, std::vector<Path>>& inputs, std::optional<std::string> channel,
         bool skip_bad_steps, const OptionalPath& result, std::optional<double> position_m,
         int lines_before_header, bool units_row, std::map<std::string, std::string> columns,
         bool keep_flagged_levels, const OptionalPath& output, py::object progress) {
        PythonRun run(std::move(progress));
        workflow::MeasureBackboneRequest request;
        if (const auto* one = std::get_if<Path>(&inputs))
          request.inputs = {one->string()};
        else
          for (const Path& input : std::get<std::vector<Path>>(inputs)) request.inputs.push_back(input.string());
        request.channel = channel.value_or("");
        request.skip_bad_steps = skip_bad_steps;
        request.result_file = TextOf(result);
        request.position_m = position_m.value_or(-1.0);
        request.table.layout.lines_before_header = lines_before_header;
        request.table.layout.units_row = units_row;
        request.table.layout.declared_in = "the arguments (lines_before_header, units_row)";
        for (const auto& [role, column] : columns) request.table.columns.Assign(role + "=" + column);
        request.keep_flagged_levels = keep_flagged_levels;
        request.output = Prefix(run, output);
        return RunWorkflow(run, request, workflow::MeasureBackbone, MeasuredToPython, request.output + ".json", output);
      },
      py::arg("inputs"), py::kw_only(), py::arg("channel") = py::none(), py::arg("skip_bad_steps") = false,
      py::arg("result") = py::none(), py::arg("position_m") = py::none(), py::arg("lines_before_header") = 0,
      py::arg("units_row") = false, py::arg("columns") = std::map<std::string, std::string>{},
      py::arg("keep_flagged_levels") = false, py::arg("output") = py::none(), py::arg("progress") = py::none(),
      R"(The measured backbone, model-free, as `beamid backbone --measured` (docs/backbone.md): per level the
phase-resonance point, the peak and the damping ratio (quadrature, local single-mode fit, half-power), and
across levels a single-nonlinear-mode fit and the damping trend.

Arguments (the command line's defaults):
  inputs               a campaign folder, a phasors file of extract, or first-harmonic CSV tables (a list,
                       one per level; docs/phasor-table.md)
  channel              the response channel of a campaign or phasors file (None: the first sensor not ignored)
  skip_bad_steps       of a campaign: leave out the steps whose recordings hold errors
  result               an identified model's result.json whose backbone is overlaid (None: none)
  position_m           the tables' sensor position [m] for that overlay (None: not given)
  lines_before_header  of tables: lines above the header, skipped
  units_row            of tables: the line under the header gives the units
  columns              of tables: {role: column}, role frequency, excitation, response or phase, column the
                       header text or its number from 1 ('3'); --column ROLE=COLUMN
  keep_flagged_levels  keep flagged levels in the cross-level fit and the damping trend
  output               also keep PREFIX.json, PREFIX.csv and PREFIX_curves.csv (None: not kept)
  progress             None or a callable progress(task, fraction, what)

Returns a dict: channel, response_quantity, excitation_quantity,
excitation_column (the CSV's name of excitation_amplitude), levels (per
level: level, control, num_points, quadrature_frequency_hz [Hz],
amplitude_m [m], response_amplitude (SI), excitation_amplitude (SI),
zeta_quadrature, zeta_local, zeta_half_power, zeta [-], peak_frequency_hz,
local_natural_frequency_hz [Hz], each with its σ under *_std*; NaN where not
estimated; regeneration_relative_rms, in_global_fit, flags (kind, quantity,
message), measured_frf (frequency_hz, receptance_m_N, phase_rad arrays)),
fit_form, damping_trend (verdict, damping_ratio_verdict, z, damping_rate_z,
note), min_amplitude_m, max_amplitude_m, warnings, document (PREFIX.json),
output, run_warnings, notes. beamid.to_pandas(backbone) gives the levels'
table as PREFIX.csv holds it.)");

  module.def(
      "model_backbone",
      [](const Path& model, double min_theta_rad, double max_theta_rad, int points, int harmonics,
         const OptionalPath& output, py::object progress) {
        PythonRun run(std::move(progress));
        workflow::TraceBackboneRequest request{.model_file = model.string(),
                                               .min_theta_rad = min_theta_rad,
                                               .max_theta_rad = max_theta_rad,
                                               .points = points,
                                               .harmonics = harmonics,
                                               .output = Prefix(run, output)};
        // As the program: the partial backbone is written, the run still failed.
        const auto checked = [](const workflow::TraceBackboneOutcome& outcome) {
          if (!outcome.Complete())
            throw NumericalError("the backbone stopped early (" + outcome.summary.message +
                                 "); try a smaller --max-theta-rad or fewer harmonics");
          return ModelBackboneToPython(outcome.file);
        };
        return RunWorkflow(run, request, workflow::TraceModelBackbone, checked, request.output + ".json", output);
      },
      py::arg("model"), py::kw_only(), py::arg("min_theta_rad") = 1e-5, py::arg("max_theta_rad") = 2e-2,
      py::arg("points") = 200, py::arg("harmonics") = 7, py::arg("output") = py::none(),
      py::arg("progress") = py::none(),
      R"(A model file's backbone by exact harmonic balance (phase resonance), with the corrected
multiple-scales backbone beside it, as `beamid backbone MODEL` (docs/model-file.md).

Arguments (the command line's defaults):
  model          the model file (JSON)
  min_theta_rad  smallest amplitude of θ = y'(L) [rad] (1e-12..1)
  max_theta_rad  largest amplitude of θ [rad] (1e-12..1)
  points         number of amplitudes (2..10000)
  harmonics      kept in the balance (1..50; -H)
  output         also keep PREFIX.csv and PREFIX.json (None: not kept)
  progress       None or a callable progress(task, fraction, what)

Returns a dict: model, harmonics (H), complete, theta_amplitude_rad [rad],
frequency_hz [Hz], force_N [N] (signed), multiple_scales_frequency_hz [Hz]
(NaN where there is none; arrays over the points), theta_rad (complex,
points × H+1, harmonics 0..H [rad]), sensors (per channel: position_m [m],
displacement_m (complex, points × H+1 [m])), document (PREFIX.json), output,
run_warnings, notes. Raises beamid.NumericalError when the backbone stopped
early (the program's exit code 3).)");
}

}  // namespace beamid::python
