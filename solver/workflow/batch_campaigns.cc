#include "solver/workflow/batch_campaigns.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <fstream>
#include <mutex>
#include <set>
#include <system_error>
#include <thread>

#include <fmt/core.h>

#include "hb/errors.h"
#include "hb/file_stem.h"
#include "hb/option_checks.h"
#include "solver/estimation/result_io.h"
#include "solver/report/external_program.h"
#include "solver/workflow/output_paths.h"

namespace beamid::workflow {
namespace {

namespace fs = std::filesystem;

constexpr int kMaxJobs = 256;

// The folder as one absolute path, without a trailing separator ("spec/" and "spec" are one campaign).
fs::path Absolute(const std::string& folder) {
  fs::path path = fs::weakly_canonical(fs::absolute(folder));
  return path.has_filename() ? path : path.parent_path();
}

// The last error the program gave on stderr ("beamid: error: TEXT", or
// failed, environment, misfit: hb/errors.h's classes), else its last line;
// "" when it wrote nothing.
std::string LastError(const fs::path& stderr_file) {
  constexpr std::string_view kPrefix = "beamid: ";
  std::ifstream in(stderr_file);
  std::string line, last, error;
  while (std::getline(in, line)) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    const std::size_t at = line.find(": ", kPrefix.size());
    if (line.starts_with(kPrefix) && at != std::string::npos) error = line.substr(at + 2);
    if (!line.empty() && line.find('\r') == std::string::npos) last = line;
  }
  return error.empty() ? last : error;
}

// A campaign's folder is no place for results: they would mix with its recordings.
void RefuseCampaignFolder(const fs::path& output) {
  std::error_code error;
  if (fs::exists(output / "campaign.json", error))
    throw InputError("-o " + output.string() +
                     " holds a campaign (campaign.json): give a folder of its own for the results");
}

std::string Joined(const std::vector<std::string>& channels) {
  std::string text;
  for (const std::string& c : channels) text += (text.empty() ? "" : ",") + c;
  return text;
}

std::string ExitText(int status) {
  return status > 128 ? fmt::format("ended by signal {}", status - 128) : fmt::format("exited with {}", status);
}

// The folder of each campaign under the output: its folder's name, made a
// safe file name, with "-2", "-3", ... where two campaigns of this run share
// a name or an earlier run's folder holds another campaign.
std::vector<std::string> EntryFolders(const BatchRequest& request) {
  // Never the summary's own names.
  std::set<std::string> taken = {std::string(kBatchSummaryCsv), std::string(kBatchIndexHtml)};
  std::vector<std::string> folders;
  for (const std::string& campaign : request.campaigns) {
    const fs::path absolute = Absolute(campaign);
    for (;;) {
      const std::string stem = hb::UniqueFileStem(absolute.filename().string(), "campaign_", taken);
      const fs::path entry = fs::path(request.output) / stem / kBatchEntryFileName;
      std::error_code error;
      if (!fs::exists(entry, error)) {
        folders.push_back(stem);
        break;
      }
      try {
        if (ReadBatchEntry(entry).campaign == absolute.string()) {
          folders.push_back(stem);
          break;
        }
      } catch (const InputError&) {
        // An unreadable entry is another run's: leave it.
      }
    }
  }
  return folders;
}

// One campaign: identify (and report) in processes of their own, and what
// happened written as batch.json.
BatchEntry RunCampaign(const BatchRequest& request, const std::string& campaign, const fs::path& folder) {
  const auto start = std::chrono::steady_clock::now();
  BatchEntry entry{.campaign = Absolute(campaign).string(), .errors_file = "errors.txt"};
  fs::create_directories(folder);
  // An earlier run's files must not pass for this run's.
  for (const char* stale :
       {"batch.json", "result.json", "parameters.csv", "report.html", "errors.txt", "report_errors.txt"})
    fs::remove(folder / stale);
  std::vector<std::string> arguments = {"-q", "identify", entry.campaign, "-o", (folder / "result.json").string(),
                                        "--csv", (folder / "parameters.csv").string(), "--workers", "1",
                                        "--model", request.model, "-H", std::to_string(request.harmonics)};
  if (!request.fit_channels.empty()) arguments.insert(arguments.end(), {"--fit", Joined(request.fit_channels)});
  if (!request.validate_channels.empty())
    arguments.insert(arguments.end(), {"--validate", Joined(request.validate_channels)});
  entry.exit_code = solver::RunExternalProgram(
      {.program = request.program, .arguments = arguments, .stderr_file = folder / entry.errors_file});
  bool written =
      (entry.exit_code == 0 || entry.exit_code == kExitModelMissesData) && fs::exists(folder / "result.json");
  std::string error;
  if (written) {
    try {
      entry.campaign_name = solver::ReadResultFile(folder / "result.json").campaign.name;
    } catch (const InputError& e) {
      written = false;  // a result the summary could not read is none
      error = e.what();
    }
  }
  if (written) {
    entry.status = entry.exit_code == 0 ? BatchStatus::kFitted : BatchStatus::kMisfit;
    entry.result_file = "result.json";
  } else {
    entry.status = BatchStatus::kFailed;
    if (error.empty()) error = LastError(folder / entry.errors_file);
    entry.message = error.empty() ? "beamid identify " + ExitText(entry.exit_code) : error;
  }
  if (written && request.report) {
    const int status = solver::RunExternalProgram(
        {.program = request.program,
         .arguments = {"-q", "report", (folder / entry.result_file).string(), "-o", (folder / "report.html").string()},
         .stderr_file = folder / "report_errors.txt"});
    if (status == 0) {
      entry.report_file = "report.html";
    } else {
      const std::string report_error = LastError(folder / "report_errors.txt");
      entry.report_problem = report_error.empty() ? "beamid report " + ExitText(status) : report_error;
    }
  }
  entry.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  WriteBatchEntry(folder / kBatchEntryFileName, entry);
  return entry;
}

}  // namespace

void BatchRequest::Validate() const {
  if (campaigns.empty()) throw InputError("batch: give at least one campaign folder");
  if (jobs < 0 || jobs > kMaxJobs) throw InputError(fmt::format("--jobs must lie between 0 and {}", kMaxJobs));
  if (harmonics < 1 || harmonics > option_checks::kMaxHarmonics)
    throw InputError(fmt::format("-H/--harmonics must lie between 1 and {}", option_checks::kMaxHarmonics));
  if (program.empty()) throw InputError("batch: the beamid program to run is not known");
  std::set<fs::path> seen;
  OutputPaths paths;
  for (const std::string& campaign : campaigns) {
    if (campaign.empty()) throw InputError("batch: a campaign folder is empty text: give its path");
    if (!seen.insert(Absolute(campaign)).second)
      throw InputError("batch: the campaign " + campaign + " is given twice: give each once");
    paths.InputFolder(campaign);
  }
  paths.OutputFolder("-o", output).Check();
  RefuseCampaignFolder(output);
}

BatchOutcome BatchCampaigns(const BatchRequest& request, const RunObserver& observer) {
  request.Validate();
  const auto start = std::chrono::steady_clock::now();
  BatchOutcome out;
  out.folders = EntryFolders(request);
  const int n = static_cast<int>(request.campaigns.size());
  const int jobs = std::min(n, request.jobs > 0 ? request.jobs
                                                : std::max(1, static_cast<int>(std::thread::hardware_concurrency())));
  std::vector<BatchEntry> entries(static_cast<std::size_t>(n));
  std::vector<std::exception_ptr> failures(static_cast<std::size_t>(n));
  std::atomic<int> next{0};
  std::mutex mutex;
  int done = 0;
  {
    ObservedTask progress(observer, "batch");
    std::vector<std::jthread> workers;
    for (int w = 0; w < jobs; ++w)
      workers.emplace_back([&] {
        for (int i; (i = next++) < n;) {
          const auto index = static_cast<std::size_t>(i);
          try {
            entries[index] = RunCampaign(request, request.campaigns[index],
                                         fs::path(request.output) / out.folders[index]);
          } catch (...) {
            failures[index] = std::current_exception();
          }
          const std::lock_guard lock(mutex);
          ++done;
          progress.Update(static_cast<double>(done) / n,
                          fmt::format("{} {}", out.folders[index],
                                      failures[index] ? "stopped"
                                                      : schema::NameOf(entries[index].status, kBatchStatusNames)));
        }
      });
  }
  // An error of the batch itself (the disk, a program that cannot start) stops the run.
  for (const std::exception_ptr& failure : failures)
    if (failure) std::rethrow_exception(failure);
  for (const BatchEntry& e : entries) {
    out.fitted += e.status == BatchStatus::kFitted;
    out.misfit += e.status == BatchStatus::kMisfit;
    out.failed += e.status == BatchStatus::kFailed;
  }
  const auto failed = std::find_if(entries.begin(), entries.end(),
                                   [](const BatchEntry& e) { return e.status == BatchStatus::kFailed; });
  if (failed != entries.end()) {
    out.exit_code = failed->exit_code >= 2 && failed->exit_code <= 4 ? failed->exit_code : 1;
    // Its message names the campaign's files; the folder says which row it is.
    out.first_failure = out.folders[static_cast<std::size_t>(failed - entries.begin())] + ": " + failed->message;
  } else {
    out.exit_code = out.misfit > 0 ? kExitModelMissesData : 0;
  }
  out.summary = CollectBatchSummary(request.output, observer);
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

BatchSummary CollectBatchSummary(const fs::path& output, const RunObserver& observer) {
  RefuseCampaignFolder(output);
  BatchSummary summary = CollectBatch(output);
  for (const std::string& w : summary.warnings) observer.Warn("batch", w);
  WriteBatchSummary(output, summary);
  return summary;
}

}  // namespace beamid::workflow
