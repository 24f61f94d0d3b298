// beamid's kinds of failure (hb/errors.h) as Python exception classes of the
// module: beamid.InputError (a ValueError), beamid.NumericalError (an
// ArithmeticError) and beamid.EnvironmentError (an OSError), each carrying
// the text the command line prints after "beamid: error: ", "beamid: failed: "
// or "beamid: environment: ". The C++ exceptions map onto them as the
// program's exit codes do (solver/cli/main.cc).
#pragma once

#include <pybind11/pybind11.h>

namespace beamid::python {

// Creates the three classes and beamid.BeamidWarning (a UserWarning: what a
// workflow warns of, which the program prints) in `module` and registers
// the exceptions' translation.
void AddExceptionClasses(pybind11::module_& module);

// beamid.BeamidWarning, once AddExceptionClasses has made it.
pybind11::handle WarningCategory();

}  // namespace beamid::python
