// Shared by the subcommands: progress and a workflow's notices on stderr,
// the options several commands take, and JSON phasors.
//
// Progress has two forms. Text (default): on a terminal one line rewritten
// in place ("identify   42 %  start 3/8"); otherwise one line per 10 %;
// nothing with --quiet. JSON (--progress json), for programs, whatever
// --quiet says: one object per line on stderr,
//     {"event":"progress","task":"identify","fraction":0.42,"what":"start 3/8"}
//     {"event":"done","task":"identify","seconds":12.3}
// and, from main, a last line {"event":"exit","exit_code":N,"message":"..."}
// (exit codes: solver/cli/command_registry.h).
#pragma once

#include <chrono>
#include <complex>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include "solver/cli/command_registry.h"

#include "signal/campaign.h"
#include "signal/phasor_set.h"
#include "solver/estimation/damping_laws.h"
#include "solver/estimation/fit_data.h"
#include "solver/workflow/campaign_input.h"
#include "solver/workflow/run_observer.h"

namespace beamid::cli {

class Progress {
 public:
  Progress(std::string label, const GlobalOptions& global);
  ~Progress();
  // fraction in [0, 1]; what: the current piece of work, optional.
  void Update(double fraction, const std::string& what = "");
  void Done();

 private:
  std::string label_;
  bool quiet_;
  bool json_;
  bool terminal_;
  int last_percent_ = -1;
  bool done_ = false;
  std::chrono::steady_clock::time_point start_;
};

// The last JSON line of a run (--progress json).
void PrintJsonExit(int exit_code, const std::string& message);

// [re, im] pairs, the JSON form of a complex phasor everywhere in beamid.
nlohmann::json PhasorsToJson(const Eigen::VectorXcd& phasors);

// Writes text to stderr and never throws: a full or closed stderr must not
// turn a run (or its error message) into a crash. Failures are ignored.
void PrintToStderr(std::string_view text) noexcept;

// A CLI11 check: a finite number in [min, max] (CLI::Range lets NaN pass).
CLI::Validator FiniteRange(double min, double max);

// A CLI11 check for a path option: an empty path ('') is refused.
CLI::Validator NonEmptyPath();

// -H/--harmonics (the model's H, 1..50) and --fit-harmonics (K, 1..50), as
// identify and diagnose take them (their check K <= H:
// workflow::RequireFitWithinModelHarmonics).
void AddModelHarmonicsOptions(CLI::App* command, int* harmonics, int* fit_harmonics, const std::string& model_help);
// --phasor-uncertainty relative_floor|propagated (solver/estimation/fit_data.h).
void AddPhasorUncertaintyOption(CLI::App* command, solver::PhasorUncertainty* uncertainty);

// --phasors and --skip-bad-steps of a model-based command.
void AddPhasorInputOptions(CLI::App* command, workflow::PhasorInput* input);

// Each damping law's refit (accepted or rejected) and every shared
// parameter's model-form interval over the accepted laws; nothing when the
// laws were not refitted.
void PrintDampingLaws(const solver::DampingLawEnvelope& envelope);

// What a workflow tells while it runs, shown on stderr: its tasks' progress
// (Progress above, in the form --progress chooses), each warning as
// "beamid SOURCE: warning: TEXT" and each note as a line, neither with
// --quiet.
workflow::RunObserver CliObserver(const GlobalOptions& global);

}  // namespace beamid::cli
