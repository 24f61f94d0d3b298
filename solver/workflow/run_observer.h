// What a workflow tells while it runs, to whoever runs it: the task it works
// on ("extract", "identify") and how far it is, and the notices that do not
// stop it (a campaign's warnings, a step left out, a default it chose). The
// workflow never prints: the program shows these on stderr (solver/cli/
// cli_output.h), a test or another program may ignore them. Every member may
// be left empty.
#pragma once

#include <functional>
#include <string>

namespace beamid::workflow {

struct RunObserver {
  // A task begins (its label), advances (fraction in [0, 1], what it is doing,
  // possibly empty) and ends; tasks follow one another, never nest.
  std::function<void(const std::string& task)> begin;
  std::function<void(double fraction, const std::string& what)> progress;
  std::function<void()> end;
  // A warning of the named part of the run ("identify", "extract").
  std::function<void(const std::string& source, const std::string& text)> warning;
  // A line of information that is no warning (which channel a default chose).
  std::function<void(const std::string& text)> note;

  void Warn(const std::string& source, const std::string& text) const {
    if (warning) warning(source, text);
  }
  void Note(const std::string& text) const {
    if (note) note(text);
  }
};

// One task of a run, begun on construction and ended on destruction (also
// when the work throws, so that a progress display is closed).
class ObservedTask {
 public:
  ObservedTask(const RunObserver& observer, const std::string& task) : observer_(observer) {
    if (observer_.begin) observer_.begin(task);
  }
  ~ObservedTask() { End(); }
  ObservedTask(const ObservedTask&) = delete;
  ObservedTask& operator=(const ObservedTask&) = delete;

  void Update(double fraction, const std::string& what = "") const {
    if (!ended_ && observer_.progress) observer_.progress(fraction, what);
  }
  void End() {
    if (ended_) return;
    ended_ = true;
    if (observer_.end) observer_.end();
  }

 private:
  const RunObserver& observer_;
  bool ended_ = false;
};

}  // namespace beamid::workflow
