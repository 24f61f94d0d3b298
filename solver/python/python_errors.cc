#include "solver/python/python_errors.h"

#include <exception>
#include <filesystem>
#include <new>
#include <stdexcept>
#include <string>
#include <system_error>

#include <nlohmann/json.hpp>

#include "hb/errors.h"

namespace py = pybind11;

namespace beamid::python {
namespace {
PyObject* warning_category = nullptr;  // owned by the module, which holds it as an attribute
}  // namespace

py::handle WarningCategory() { return warning_category; }

void AddExceptionClasses(py::module_& module) {
  warning_category = PyErr_NewExceptionWithDoc(
      "beamid.BeamidWarning", "What a run of beamid warns of: the result stands, the engineer should look.",
      PyExc_UserWarning, nullptr);
  if (warning_category == nullptr) throw py::error_already_set();
  module.add_object("BeamidWarning", py::handle(warning_category));
  // Static: the translator below outlives this call and refers to them.
  static py::exception<InputError> input_error(module, "InputError", PyExc_ValueError);
  static py::exception<NumericalError> numerical_error(module, "NumericalError", PyExc_ArithmeticError);
  static py::exception<EnvironmentError> environment_error(module, "EnvironmentError", PyExc_OSError);
  input_error.doc() =
      "Bad input the user can fix in a file or an argument; the message names the file, channel or argument and "
      "the fix (the command line's exit code 2).";
  numerical_error.doc() =
      "A computation on valid input did not converge or has no solution there (the command line's exit code 3).";
  environment_error.doc() =
      "The machine refused: a missing program, a full disk, a failed fork, too little memory (the command line's "
      "exit code 4).";
  // The same order and the same texts as the program's main(): a script that
  // moves from the command line to Python sees the same messages.
  py::register_local_exception_translator([](std::exception_ptr failure) {
    try {
      if (failure) std::rethrow_exception(failure);
    } catch (const std::invalid_argument& e) {  // InputError and the readers' older throws
      input_error(e.what());
    } catch (const nlohmann::json::exception& e) {
      input_error((std::string("a JSON input holds a value beamid cannot use: ") + e.what()).c_str());
    } catch (const NumericalError& e) {
      numerical_error(e.what());
    } catch (const EnvironmentError& e) {
      environment_error(e.what());
    } catch (const std::system_error& e) {  // std::filesystem::filesystem_error among them
      environment_error(e.what());
    } catch (const std::bad_alloc&) {
      environment_error("not enough memory for this problem: use fewer steps, harmonics or samples");
    }
  });
}

}  // namespace beamid::python
