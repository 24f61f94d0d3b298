#include "signal/campaign_extractor.h"

#include "hb/errors.h"
#include "hb/option_checks.h"
#include "signal/input_error.h"

#include <algorithm>
#include <atomic>
#include <exception>
#include <mutex>
#include <stdexcept>
#include <thread>
#include <vector>

#include "signal/input_error.h"
#include "signal/recording.h"

namespace beamid::signal {

void ExtractOptions::Validate() const {
  estimator.Validate();
  checks.Validate();
  // The bound of identify's --threads, which names the same kind of pool.
  option_checks::RequireInRange("ExtractOptions.num_threads (0: one per core)", num_threads, 0, 256);
}

PhasorSet ExtractCampaign(const Campaign& campaign, const ExtractOptions& options) {
  options.Validate();
  const std::size_t total = campaign.steps.size();
  PhasorSet set;
  set.campaign = campaign.name;
  set.num_harmonics = options.estimator.num_harmonics;
  set.steps.resize(total);
  std::vector<std::exception_ptr> errors(total);
  std::atomic<std::size_t> next{0};
  std::atomic<bool> failed{false};
  std::mutex progress_mutex;
  std::size_t done = 0;

  auto work = [&] {
    for (std::size_t i = next++; i < total && !failed; i = next++) {
      const Step& step = campaign.steps[i];
      try {
        const Recording recording = ReadRecording(campaign, step, options.checks);
        try {
          set.steps[i] = EstimateStepPhasors(recording, campaign, step, options.estimator);
          if (!recording.ignored_columns.empty()) {
            std::string columns;
            for (const auto& c : recording.ignored_columns) columns += (columns.empty() ? "" : ", ") + c;
            set.steps[i].quality.warnings.push_back("columns no channel uses, ignored: " + columns);
          }
        } catch (const NumericalError& e) {
          // Estimation fails on a recording only when its data do not hold
          // a steady sine: the user's to fix, in that file.
          throw InputError(recording.file, "", e.what(),
                           "look for wild samples, a missing excitation or a record cut short in this file");
        }
        if (options.progress) {
          std::lock_guard lock(progress_mutex);
          options.progress(++done, total, set.steps[i]);
        }
      } catch (...) {
        // Nothing may escape a worker thread: keep the error for the caller.
        errors[i] = std::current_exception();
        failed = true;
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
  for (const auto& error : errors)
    if (error) std::rethrow_exception(error);
  return set;
}

}  // namespace beamid::signal
