// simulate: a scenario's stepped-sine test run through the independent
// time-domain simulator and written as a campaign folder, as `beamid
// simulate SCENARIO -o FOLDER` (solver/workflow/simulate_campaign.h).
#include <string>

#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "solver/python/module_functions.h"
#include "solver/python/python_run.h"
#include "solver/workflow/simulate_campaign.h"

namespace py = pybind11;
using namespace pybind11::literals;

namespace beamid::python {

void AddSimulateFunctions(py::module_& module) {
  module.def(
      "simulate",
      [](const Path& scenario, const Path& output, bool overwrite, py::object progress) {
        PythonRun run(std::move(progress));
        const workflow::SimulateRequest request{
            .scenario = scenario.string(), .output = output.string(), .overwrite = overwrite};
        const auto to_python = [](const workflow::SimulateOutcome& outcome) {
          return py::dict("kind"_a = "simulation", "num_steps"_a = outcome.num_steps,
                          "unsettled_steps"_a = outcome.unsettled_steps, "bytes_written"_a = outcome.bytes_written,
                          "clipped_samples"_a = outcome.clipped_samples);
        };
        const auto simulate = [](const workflow::SimulateRequest& r, const workflow::RunObserver& observer) {
          return workflow::SimulateCampaign(r, observer);
        };
        return RunWorkflow(run, request, simulate, to_python, output / "campaign.json", output);
      },
      py::arg("scenario"), py::arg("output"), py::kw_only(), py::arg("overwrite") = false,
      py::arg("progress") = py::none(),
      R"(A scenario's stepped-sine test run through the independent time-domain simulator and written as a
campaign folder (campaign.json, one recording per step, truth.json), as `beamid simulate SCENARIO -o OUTPUT`
(docs/simulator.md).

Arguments (the command line's defaults):
  scenario   the scenario file (JSON; examples/scenarios)
  output     the campaign folder to write
  overwrite  replace a campaign already in output (--overwrite); never an input
  progress   None or a callable progress(task, fraction, what), once per step

Returns a dict: num_steps, unsettled_steps (cut at timing.settle_max_s before
settling; truth.json marks them), bytes_written, clipped_samples (by the
simulated ADC), document (campaign.json), output, run_warnings, notes.)");
}

}  // namespace beamid::python
