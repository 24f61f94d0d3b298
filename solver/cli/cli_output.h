// Shared by the subcommands: progress on stderr, CSV/JSON writing with clear
// errors, and the conversion of displacement phasors to the other quantities.
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

// Writes text to a file, creating its folder; throws std::invalid_argument
// naming the path if it cannot.
void WriteTextFile(const std::filesystem::path& path, const std::string& text);

// Writes text to stderr and never throws: a full or closed stderr must not
// turn a run (or its error message) into a crash. Failures are ignored.
void PrintToStderr(std::string_view text) noexcept;

// A CLI11 check: a finite number in [min, max] (CLI::Range lets NaN pass).
CLI::Validator FiniteRange(double min, double max);

// A CLI11 check for a path option: an empty path ('') is refused.
CLI::Validator NonEmptyPath();

// -H/--harmonics (the model's H, 1..50) and --fit-harmonics (K, 1..50), as
// identify and diagnose take them; and the check, before any work, that the
// model holds every fitted harmonic (K <= H).
void AddModelHarmonicsOptions(CLI::App* command, int* harmonics, int* fit_harmonics, const std::string& model_help);
void RequireFitWithinModelHarmonics(int fit_harmonics, int harmonics);

// campaign.json of a folder (its warnings printed on stderr, signal::
// Campaign::warnings) and the channels a fit uses: --fit as given, or every
// sensor neither ignored nor held out; the fitted and held-out sensors are
// marked as analysed, so that only their recordings' problems stop the run
// (signal::Campaign::Use). Throws InputError for a channel both fitted and
// held out (its "prediction" would be a fit) and for a fit with no channel
// left.
struct CampaignForAnalysis {
  signal::Campaign campaign;
  std::vector<std::string> fit_channels;
};
CampaignForAnalysis ReadCampaignForAnalysis(const std::string& command, const std::string& folder,
                                            const std::vector<std::string>& fit_channels,
                                            const std::vector<std::string>& validate_channels,
                                            const GlobalOptions& global);

// campaign.json of a folder, its warnings printed on stderr unless --quiet
// (a recording that is a byte copy of another step's).
signal::Campaign ReadCampaignAndWarn(const std::string& command, const std::filesystem::path& folder,
                                     const GlobalOptions& global);

// Where a model-based command takes its phasors from.
struct PhasorInput {
  std::string phasors_file;     // --phasors: the output of `beamid extract`; empty: extract
  bool skip_bad_steps = false;  // --skip-bad-steps: analyse the steps whose recordings hold no error
};
void AddPhasorInputOptions(CLI::App* command, PhasorInput* input);

// The phasors of a campaign: read from input.phasors_file when given (and
// checked to be this campaign's: its steps, and its campaign_sha256 against
// the campaign's content hash, signal/campaign_identity.h), else extracted with harmonics
// 1..num_harmonics and progress on stderr. The steps left out (skipped) are
// listed on stderr unless --quiet.
signal::PhasorSet ReadOrExtractPhasors(const signal::Campaign& campaign, const PhasorInput& input, int num_harmonics,
                                       const GlobalOptions& global);

// The steps an extraction left out, one warning line each on stderr.
// Each damping law's refit (accepted or rejected) and every shared
// parameter's model-form interval over the accepted laws; nothing when the
// laws were not refitted.
void PrintDampingLaws(const solver::DampingLawEnvelope& envelope);

void PrintSkippedSteps(const std::string& command, const signal::PhasorSet& phasors, const GlobalOptions& global);

}  // namespace beamid::cli
