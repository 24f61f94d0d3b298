// frc: a model file's frequency response curves by harmonic balance and
// pseudo-arclength continuation, one per force level, as `beamid frc MODEL`
// (solver/workflow/trace_response_curves.h).
#include <algorithm>
#include <complex>
#include <optional>
#include <string>
#include <vector>

#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "hb/errors.h"
#include "hb/frc_file.h"
#include "solver/python/module_functions.h"
#include "solver/python/python_arrays.h"
#include "solver/python/python_errors.h"
#include "solver/python/python_run.h"
#include "solver/workflow/trace_response_curves.h"

namespace py = pybind11;
using namespace pybind11::literals;

namespace beamid::python {
namespace {

// One curve's points as arrays over the points; complex phasors as
// points × (H + 1) matrices, harmonics 0..H.
py::dict CurveToPython(const hb::FrcFile& file, const hb::FrcCurve& curve) {
  const std::size_t n = curve.points.size();
  const auto columns = static_cast<std::size_t>(file.harmonics) + 1;
  py::array_t<double> frequency = NanArray(n);
  py::array_t<bool> stable(static_cast<py::ssize_t>(n));
  auto theta = NanMatrix<std::complex<double>>(n, columns);
  std::vector<py::array_t<std::complex<double>>> displacement, acceleration;
  for (std::size_t j = 0; j < file.sensors.size(); ++j) {
    displacement.push_back(NanMatrix<std::complex<double>>(n, columns));
    acceleration.push_back(NanMatrix<std::complex<double>>(n, columns));
  }
  for (std::size_t i = 0; i < n; ++i) {
    const hb::FrcPoint& p = curve.points[i];
    const auto row = static_cast<py::ssize_t>(i);
    frequency.mutable_at(row) = p.frequency_hz;
    stable.mutable_at(row) = p.stable;
    for (std::size_t k = 0; k < std::min(p.theta_rad.size(), columns); ++k)
      theta.mutable_at(row, static_cast<py::ssize_t>(k)) = p.theta_rad[k];
    for (std::size_t j = 0; j < std::min(p.sensors.size(), displacement.size()); ++j)
      for (std::size_t k = 0; k < std::min(p.sensors[j].displacement_m.size(), columns); ++k) {
        displacement[j].mutable_at(row, static_cast<py::ssize_t>(k)) = p.sensors[j].displacement_m[k];
        acceleration[j].mutable_at(row, static_cast<py::ssize_t>(k)) = p.sensors[j].acceleration_m_s2[k];
      }
  }
  py::dict by_sensor;
  for (std::size_t j = 0; j < file.sensors.size(); ++j)
    by_sensor[py::str(file.sensors[j].channel)] =
        py::dict("position_m"_a = file.sensors[j].position_m, "displacement_m"_a = displacement[j],
                 "acceleration_m_s2"_a = acceleration[j]);
  return py::dict("force_N"_a = curve.force_N, "turning_points"_a = curve.turning_points,
                  "complete"_a = curve.complete, "frequency_hz"_a = frequency, "stable"_a = stable,
                  "theta_rad"_a = theta, "sensors"_a = by_sensor);
}

py::dict FrcToPython(const workflow::FrcOutcome& outcome) {
  const hb::FrcFile& file = outcome.file;
  py::list curves;
  for (const hb::FrcCurve& curve : file.curves) curves.append(CurveToPython(file, curve));
  return py::dict("kind"_a = "frc", "model"_a = file.model, "harmonics"_a = file.harmonics,
                  "first_natural_frequency_hz"_a = file.first_natural_frequency_hz, "curves"_a = curves);
}

}  // namespace

void AddFrcFunctions(py::module_& module) {
  module.def(
      "frc",
      [](const Path& model, std::vector<double> force_N, std::optional<double> from_hz, std::optional<double> to_hz,
         int harmonics, int max_points, const OptionalPath& output, py::object progress) {
        PythonRun run(std::move(progress));
        workflow::FrcRequest request{.model_file = model.string(),
                                     .force_levels_N = std::move(force_N),
                                     .from_hz = from_hz.value_or(0.0),
                                     .to_hz = to_hz.value_or(0.0),
                                     .harmonics = harmonics,
                                     .max_points = max_points,
                                     .output = run.OutputPath(output, "frc")};
        const auto trace = [](const workflow::FrcRequest& r, const workflow::RunObserver& observer) {
          return workflow::TraceResponseCurves(r, observer);
        };
        // As the program: the partial curves are written, the run still failed.
        const auto checked = [](const workflow::FrcOutcome& outcome) {
          if (!outcome.Incomplete().empty())
            throw NumericalError(outcome.Incomplete() +
                                 "; try a smaller range, more max_points or fewer harmonics");
          return FrcToPython(outcome);
        };
        return RunWorkflow(run, request, trace, checked, request.output + ".json", output);
      },
      py::arg("model"), py::kw_only(), py::arg("force_N") = std::vector<double>{0.5, 1.0, 2.0},
      py::arg("from_hz") = py::none(), py::arg("to_hz") = py::none(), py::arg("harmonics") = 7,
      py::arg("max_points") = 3000, py::arg("output") = py::none(), py::arg("progress") = py::none(),
      R"(A model file's frequency response curves by harmonic balance and pseudo-arclength continuation,
stable and unstable branches, one curve per force level, as `beamid frc MODEL` (docs/model-file.md).

Arguments (the command line's defaults):
  model       the model file (JSON)
  force_N     the force amplitudes [N], one curve each (--force-N)
  from_hz     the band's lower end [Hz] (None: 0.9 × the first natural frequency)
  to_hz       the band's upper end [Hz] (None: 1.1 × the first natural frequency)
  harmonics   kept in the balance (1..50; -H)
  max_points  per curve (2..100000)
  output      also keep PREFIX.csv and PREFIX.json (None: not kept)
  progress    None or a callable progress(task, fraction, what)

Returns a dict: model, harmonics (H), first_natural_frequency_hz [Hz],
curves (a list in force order; each: force_N [N], turning_points, complete,
frequency_hz [Hz] and stable (bool) over the points, theta_rad (complex,
points × H+1, harmonics 0..H [rad]), sensors (per channel: position_m [m],
displacement_m [m] and acceleration_m_s2 [m/s²], complex, points × H+1)),
document (PREFIX.json), output, run_warnings, notes. Raises
beamid.NumericalError when a curve stopped early (the program's exit code
3; with output given, the partial curves are kept as the program keeps them).)");
}

}  // namespace beamid::python
