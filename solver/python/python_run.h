// One call of a workflow from Python: the work runs without the GIL (other
// Python threads go on), its progress goes to an optional Python callback
// progress(task, fraction, what), Ctrl-C is honoured at each progress report
// (the work is abandoned by an exception that unwinds it, and the caller gets
// KeyboardInterrupt), and the workflow's warnings and notes are kept for the
// result. A file the caller did not ask for is written into a private
// temporary folder that goes with the run.
#pragma once

#include <atomic>
#include <exception>
#include <filesystem>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include <pybind11/pybind11.h>
#include <pybind11/stl/filesystem.h>
#include <sys/types.h>

#include "solver/python/python_errors.h"
#include "solver/report/temp_folder.h"
#include "solver/workflow/run_observer.h"

namespace beamid::python {

// A path argument: a str or any os.PathLike (pathlib.Path), as
// pybind11/stl/filesystem.h converts it; optional ones are None when not given.
using Path = std::filesystem::path;
using OptionalPath = std::optional<std::filesystem::path>;

// An optional path as a workflow's request holds it: "" when not given.
inline std::string TextOf(const OptionalPath& path) { return path ? path->string() : std::string(); }

// An optional path as a result holds it: None when not given.
inline pybind11::object PythonOf(const OptionalPath& path) {
  return path ? pybind11::object(pybind11::str(path->string())) : pybind11::object(pybind11::none());
}

class PythonRun {
 public:
  // progress: None or a callable (task: str, fraction: float, what: str).
  // Called with the GIL held.
  explicit PythonRun(pybind11::object progress);
  PythonRun(const PythonRun&) = delete;
  PythonRun& operator=(const PythonRun&) = delete;

  // `path` when the caller gave one, else `name` in the run's temporary folder.
  std::string OutputPath(const OptionalPath& path, const std::string& name);

  // Runs work(observer) with the GIL released and returns its value. A Python
  // exception of the callback, or KeyboardInterrupt, is raised once the work
  // has unwound; beamid's exceptions pass through to the module's translator.
  // Calls from several Python threads run one after the other: Ipopt's
  // linear solver (MUMPS) keeps global state that forbids two fits at once.
  // A call from a progress callback, which would wait for itself, raises
  // RuntimeError.
  template <typename Work>
  auto Run(Work&& work) -> decltype(work(std::declval<const workflow::RunObserver&>())) {
    RefuseCallFromCallback();
    try {
      pybind11::gil_scoped_release release;
      std::lock_guard lock(WorkMutex());
      return work(observer_);
    } catch (const Abandoned&) {
      RaisePythonError();
    }
  }

  // What the workflow told besides progress: "SOURCE: TEXT" per warning, and
  // each note, in order; each warning is also issued as a Python warning
  // (beamid.BeamidWarning), as the program prints it.
  pybind11::list Warnings() const;
  pybind11::list Notes() const;
  void IssueWarnings(const pybind11::handle& category) const;

 private:
  // Thrown through the workflow when the callback raised or Ctrl-C was
  // pressed. Not a std::exception: no `catch (const std::exception&)` of a
  // workflow (a failed start, a failed refit) may take it for the work's own.
  struct Abandoned {};

  void Report(double fraction, const std::string& what);
  [[noreturn]] void RaisePythonError();
  static std::mutex& WorkMutex();
  static void RefuseCallFromCallback();

  pybind11::object callback_;
  pid_t pid_;  // a forked worker process (solver/estimation/internal/worker_processes.h) never calls Python
  workflow::RunObserver observer_;
  std::mutex mutex_;  // the extraction reports from its worker threads
  std::string task_;
  std::vector<std::string> warnings_, notes_;
  std::atomic<bool> abandoned_{false};
  std::exception_ptr python_error_;  // a pybind11::error_already_set
  std::unique_ptr<solver::TempFolder> temp_folder_;
};

// The JSON text of a file beamid wrote, as Python objects (json.loads).
pybind11::object LoadJsonFile(const std::filesystem::path& path);

// What every function that writes a file returns beside its own fields:
// document (json_file as Python objects), output (where the caller kept it,
// or None), run_warnings and notes.
void AddRunFields(pybind11::dict& result, const std::filesystem::path& json_file, const OptionalPath& output,
                  const PythonRun& run);

// A whole call: work(request, observer) under `run`, its warnings issued,
// its outcome converted by to_python (which may throw, as the program does
// for an outcome it turns into an exit code) and the run's fields added.
template <typename Request, typename Work, typename ToPython>
pybind11::dict RunWorkflow(PythonRun& run, const Request& request, Work&& work, ToPython&& to_python,
                           const std::filesystem::path& json_file, const OptionalPath& output) {
  const auto outcome = run.Run([&](const workflow::RunObserver& observer) { return work(request, observer); });
  run.IssueWarnings(WarningCategory());
  pybind11::dict result = to_python(outcome);
  AddRunFields(result, json_file, output, run);
  return result;
}

}  // namespace beamid::python
