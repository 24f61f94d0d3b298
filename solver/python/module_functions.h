// The functions of the Python module beamid, one file per concept: each adds
// its functions (with their keyword arguments, the command line's defaults
// and docstrings in SI units) to the module. docs/python.md describes them.
#pragma once

#include <pybind11/pybind11.h>

namespace beamid::python {

// read_campaign, extract (python_campaign.cc).
void AddCampaignFunctions(pybind11::module_& module);
// identify, predict, diagnose (python_fit.cc).
void AddFitFunctions(pybind11::module_& module);
// measured_backbone, model_backbone (python_backbone.cc).
void AddBackboneFunctions(pybind11::module_& module);
// simulate (python_simulate.cc).
void AddSimulateFunctions(pybind11::module_& module);
// frc (python_frc.cc).
void AddFrcFunctions(pybind11::module_& module);

}  // namespace beamid::python
