// The summary of `beamid batch`: one row per campaign folder of the output
// folder (each holds a batch.json, solver/workflow/batch_entry.h), read back
// from the folders, so that it is the same whether the campaigns ran in one
// batch, in several, or as the tasks of a cluster's job array. Written as
// summary.csv (for spreadsheets and pandas; docs/batch.md lists its columns)
// and index.html (the same table, each campaign linking its report).
//
// A row shows the identified parameters with σ and the 95 % interval under
// the damping law the data accept (the one the report draws as the answer),
// the reduced χ² and the verdict; a fit that misses the data beyond their
// noise is marked as such, a failed campaign carries the program's message.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "solver/workflow/batch_entry.h"

namespace beamid::workflow {

struct BatchParameter {
  std::string name, unit;
  double value = 0.0, std = 0.0, lower_95 = 0.0, upper_95 = 0.0;
};

struct BatchRow {
  std::string folder;  // the entry's folder name under the output folder
  BatchEntry entry;
  std::vector<BatchParameter> parameters;  // empty without a result
  std::string damping_law;                 // the law the parameters are under ("" without a result)
  double reduced_chi_square = 0.0;         // NaN without a result
  bool within_noise = false;
  std::string verdict;
};

struct BatchSummary {
  std::vector<BatchRow> rows;  // by folder name
  std::vector<std::string> warnings;  // a folder whose batch.json or result could not be read
  int Count(BatchStatus status) const;
};

// Reads every OUTPUT/*/batch.json and the result each names. A folder
// without batch.json is not a campaign's and is passed over; one whose
// files cannot be read is a warning, not an abort: the other rows stand.
BatchSummary CollectBatch(const std::filesystem::path& output_folder);

std::string BatchSummaryCsv(const BatchSummary& summary);
std::string BatchIndexHtml(const BatchSummary& summary, const std::string& title);

// Writes OUTPUT/summary.csv and OUTPUT/index.html, each atomically.
void WriteBatchSummary(const std::filesystem::path& output_folder, const BatchSummary& summary);

inline constexpr std::string_view kBatchSummaryCsv = "summary.csv";
inline constexpr std::string_view kBatchIndexHtml = "index.html";

}  // namespace beamid::workflow
