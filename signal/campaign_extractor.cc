#include "signal/campaign_extractor.h"

#include <algorithm>
#include <atomic>
#include <exception>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <thread>
#include <vector>

#include "hb/errors.h"
#include "hb/option_checks.h"
#include "signal/input_error.h"
#include "signal/quality_finding.h"
#include "signal/recording.h"

namespace beamid::signal {

void ExtractOptions::Validate() const {
  estimator.Validate();
  checks.Validate();
  // The bound of identify's --threads, which names the same kind of pool.
  option_checks::RequireInRange("ExtractOptions.num_threads (0: one per core)", num_threads, 0, 256);
}

namespace {

// The step's phasors, or an InputError naming its file.
StepPhasors ExtractStep(const Campaign& campaign, const Step& step, const ExtractOptions& options) {
  const Recording recording = ReadRecording(campaign, step, options.checks);
  StepPhasors phasors;
  try {
    phasors = EstimateStepPhasors(recording, campaign, step, options.estimator);
  } catch (const NumericalError& e) {
    // Estimation fails on a recording only when its data do not hold a
    // steady sine: the user's to fix, in that file.
    throw InputError(recording.file, "", e.what(),
                     "look for wild samples, a missing excitation or a record cut short in this file");
  }
  for (const auto& finding : recording.findings)
    (finding.severity == Severity::kWarning ? phasors.quality.warnings : phasors.quality.notes)
        .push_back(finding.Text(campaign.Use(finding.channel)));
  if (!recording.ignored_columns.empty()) {
    // A few names say what the columns are; a header of thousands stays one line.
    constexpr std::size_t kMaxNamed = 8;
    const auto& ignored = recording.ignored_columns;
    std::string columns;
    for (std::size_t i = 0; i < ignored.size() && i < kMaxNamed; ++i)
      columns += (columns.empty() ? "" : ", ") + ignored[i];
    if (ignored.size() > kMaxNamed) columns += " and " + std::to_string(ignored.size() - kMaxNamed) + " more";
    phasors.quality.warnings.push_back("columns no channel uses, ignored: " + columns);
  }
  return phasors;
}

}  // namespace

PhasorSet ExtractCampaign(const Campaign& campaign, const ExtractOptions& options) {
  options.Validate();
  const std::size_t total = campaign.steps.size();
  std::vector<std::optional<StepPhasors>> steps(total);
  std::vector<std::string> errors(total);
  std::vector<std::exception_ptr> failures(total);  // not the recording's fault: rethrown
  std::atomic<std::size_t> next{0};
  std::mutex progress_mutex;
  std::size_t done = 0;

  auto work = [&] {
    for (std::size_t i = next++; i < total; i = next++) {
      try {
        steps[i] = ExtractStep(campaign, campaign.steps[i], options);
        if (options.progress) {
          std::lock_guard lock(progress_mutex);
          options.progress(++done, total, *steps[i]);
        }
      } catch (const InputError& e) {
        errors[i] = e.what();
      } catch (...) {
        // Nothing may escape a worker thread: keep the error for the caller.
        failures[i] = std::current_exception();
      }
    }
  };
  const unsigned hardware = std::max(1u, std::thread::hardware_concurrency());
  const std::size_t num_threads =
      std::min<std::size_t>(total, options.num_threads > 0 ? static_cast<std::size_t>(options.num_threads) : hardware);
  std::vector<std::thread> threads;
  for (std::size_t t = 1; t < num_threads; ++t) threads.emplace_back(work);
  work();
  for (auto& thread : threads) thread.join();
  for (const auto& failure : failures)
    if (failure) std::rethrow_exception(failure);

  PhasorSet set;
  set.campaign = campaign.name;
  set.campaign_sha256 = campaign.sha256;
  set.num_harmonics = options.estimator.num_harmonics;
  std::string listed;
  std::size_t num_bad = 0;
  for (std::size_t i = 0; i < total; ++i) {
    if (steps[i]) {
      set.steps.push_back(std::move(*steps[i]));
      continue;
    }
    ++num_bad;
    const Step& step = campaign.steps[i];
    set.skipped.push_back({.file = step.file, .level = step.level, .nominal_frequency_hz = step.frequency_hz,
                           .reason = errors[i]});
    listed += "\n  - " + errors[i];
  }
  if (num_bad == 0) return set;
  const std::string source = (campaign.folder / "campaign.json").string();
  if (!options.skip_bad_steps)
    throw InputError(source, "", std::to_string(num_bad) + " of " + std::to_string(total) + " steps cannot be analysed",
                     "repair or record these steps again, or skip them (--skip-bad-steps) to analyse the other "
                     "steps:" + listed);
  if (set.steps.empty())
    throw InputError(source, "", "no step can be analysed", "repair or record the steps again:" + listed);
  return set;
}

}  // namespace beamid::signal
