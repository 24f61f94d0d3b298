// The extension module beamid._beamid; the package beamid (beamid/__init__.py)
// re-exports it beside its pure-Python helpers (to_pandas).
#include <pybind11/pybind11.h>

#include "hb/version.h"
#include "solver/python/module_functions.h"
#include "solver/python/python_errors.h"

PYBIND11_MODULE(_beamid, module) {
  module.doc() =
      "beamid: identify the nonlinear support of a vibrating beam from stepped-sine tests (docs/python.md).";
  module.attr("__version__") = beamid::kVersion;
  beamid::python::AddExceptionClasses(module);
  beamid::python::AddCampaignFunctions(module);
  beamid::python::AddFitFunctions(module);
  beamid::python::AddBackboneFunctions(module);
  beamid::python::AddFrcFunctions(module);
  beamid::python::AddSimulateFunctions(module);
}
