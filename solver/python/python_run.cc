#include "solver/python/python_run.h"

#include <unistd.h>

#include <stdexcept>

#include "solver/report/temp_folder.h"

namespace py = pybind11;

namespace beamid::python {
namespace {
// Set while this thread runs a progress callback.
thread_local bool in_callback = false;
}  // namespace

std::mutex& PythonRun::WorkMutex() {
  static std::mutex mutex;
  return mutex;
}

void PythonRun::RefuseCallFromCallback() {
  if (in_callback) throw std::runtime_error("a function of beamid cannot be called from a progress callback");
}

PythonRun::PythonRun(py::object progress) : callback_(std::move(progress)), pid_(::getpid()) {
  if (!callback_.is_none() && !PyCallable_Check(callback_.ptr()))
    throw py::type_error("progress must be None or a callable progress(task, fraction, what)");
  observer_.begin = [this](const std::string& task) {
    {
      std::lock_guard lock(mutex_);
      task_ = task;
    }
    Report(0.0, "");
  };
  observer_.progress = [this](double fraction, const std::string& what) { Report(fraction, what); };
  observer_.warning = [this](const std::string& source, const std::string& text) {
    std::lock_guard lock(mutex_);
    warnings_.push_back(source + ": " + text);
  };
  observer_.note = [this](const std::string& text) {
    std::lock_guard lock(mutex_);
    notes_.push_back(text);
  };
}

std::string PythonRun::OutputPath(const OptionalPath& path, const std::string& name) {
  if (path) return path->string();
  if (!temp_folder_) temp_folder_ = std::make_unique<solver::TempFolder>("python");
  return (temp_folder_->path() / name).string();
}

void PythonRun::Report(double fraction, const std::string& what) {
  if (::getpid() != pid_) return;  // a forked worker: its parent's interpreter is not its own
  if (abandoned_) throw Abandoned{};
  std::lock_guard lock(mutex_);
  py::gil_scoped_acquire acquire;
  try {
    // Ctrl-C only sets a flag; the interpreter's handler raises
    // KeyboardInterrupt here, in the main thread.
    if (PyErr_CheckSignals() != 0) throw py::error_already_set();
    if (!callback_.is_none()) {
      struct CallbackScope {
        CallbackScope() { in_callback = true; }
        ~CallbackScope() { in_callback = false; }
      } scope;
      callback_(task_, fraction, what);
    }
  } catch (const py::error_already_set&) {
    python_error_ = std::current_exception();
    abandoned_ = true;
    throw Abandoned{};
  }
}

void PythonRun::RaisePythonError() {
  std::exception_ptr error;
  {
    std::lock_guard lock(mutex_);
    error = python_error_;
  }
  std::rethrow_exception(error);
}

py::list PythonRun::Warnings() const {
  py::list list;
  for (const std::string& w : warnings_) list.append(w);
  return list;
}

py::list PythonRun::Notes() const {
  py::list list;
  for (const std::string& n : notes_) list.append(n);
  return list;
}

void PythonRun::IssueWarnings(const py::handle& category) const {
  for (const std::string& w : warnings_)
    // Level 1: the line of Python that called the module's function.
    if (PyErr_WarnEx(category.ptr(), ("beamid " + w).c_str(), 1) != 0) throw py::error_already_set();
}

py::object LoadJsonFile(const std::filesystem::path& path) {
  return py::module_::import("json").attr("loads")(solver::ReadWholeFile(path));
}

void AddRunFields(py::dict& result, const std::filesystem::path& json_file, const OptionalPath& output,
                  const PythonRun& run) {
  result["document"] = LoadJsonFile(json_file);
  result["output"] = PythonOf(output);
  result["run_warnings"] = run.Warnings();
  result["notes"] = run.Notes();
}

}  // namespace beamid::python
