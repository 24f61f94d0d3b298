// The batch use case (`beamid batch CAMPAIGN... -o OUTPUT`): the same
// analysis over many campaigns, each in processes of its own, `jobs` at a
// time. Per campaign the program runs `beamid identify` (and `beamid
// report` on its result) with the batch's options into OUTPUT/<stem>/, a
// folder named after the campaign's (hb/file_stem.h), and writes there what
// happened (batch.json, solver/workflow/batch_entry.h); then the summary of
// every folder of OUTPUT (solver/workflow/batch_summary.h).
//
// Processes, not threads: Ipopt's linear solver keeps global state that
// allows one fit per process, and a campaign that crashes or exhausts
// memory takes only its own process down. The program is started by
// posix_spawn with an argument vector (solver/report/external_program.h),
// never through a shell. Each campaign stays a folder of its own, so a
// cluster's job array runs one campaign per task with the same command and
// `beamid batch --collect OUTPUT` summarises them all afterwards
// (examples/slurm/).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "solver/workflow/batch_summary.h"
#include "solver/workflow/run_observer.h"

namespace beamid::workflow {

struct BatchRequest {
  std::vector<std::string> campaigns;  // campaign folders (each holds campaign.json)
  std::string output = "batch";        // the folder the results, summary.csv and index.html go to
  std::string program;                 // the beamid executable the campaigns run
  int jobs = 0;                        // campaigns at a time (0: one per core; up to 256)
  // identify's options, the same for every campaign (empty: identify's defaults).
  std::vector<std::string> fit_channels;
  std::vector<std::string> validate_channels;
  std::string model = "hb";
  int harmonics = 5;
  bool report = true;  // also `beamid report` each result

  // Throws InputError naming the option and the fix: no campaign, a
  // campaign given twice, jobs or harmonics out of range, an output folder
  // that is or lies inside a campaign or holds one (solver/workflow/output_paths.h).
  void Validate() const;
};

struct BatchOutcome {
  BatchSummary summary;        // of every folder of the output, this run's and earlier ones'
  std::vector<std::string> folders;  // this run's campaigns' folders under the output, in request order
  int fitted = 0, misfit = 0, failed = 0;  // of this run's campaigns
  double seconds = 0.0;
  int exit_code = 0;  // the program's: 0 every campaign fitted within noise; else the first failed one's, else 5
  std::string first_failure;  // "FOLDER: MESSAGE" of the first failed campaign in the request's order ("": none)
};

// Validates, runs every campaign (the task "batch", advancing as each
// campaign ends, with its name and status), writes each batch.json, then the
// summary. A campaign that fails is an outcome, not an error: its row
// carries the program's message.
BatchOutcome BatchCampaigns(const BatchRequest& request, const RunObserver& observer = {});

// Only the summary, from the folders OUTPUT holds (`beamid batch --collect`).
BatchSummary CollectBatchSummary(const std::filesystem::path& output, const RunObserver& observer = {});

}  // namespace beamid::workflow
