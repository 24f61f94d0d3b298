// One campaign of `beamid batch`: what was run on it and how it ended,
// written beside its results as OUTPUT/<stem>/batch.json (format
// "beamid-batch-entry/1", docs/batch.md), so that the summary can be rebuilt
// from the folders alone: a cluster's job array writes one folder per task,
// and `beamid batch --collect OUTPUT` summarises whatever the folders hold.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "hb/enum_names.h"
#include "hb/json_schema.h"
#include "hb/version.h"

namespace beamid::workflow {

// fitted: identify fitted within the noise; misfit: it fitted, but the model
// misses the data beyond their noise (exit 5, the result written: run
// `beamid diagnose` on it); failed: no result (bad input, no convergence,
// the environment; the message says which and what to fix).
enum class BatchStatus { kFitted, kMisfit, kFailed };
inline constexpr schema::Name<BatchStatus> kBatchStatusNames[] = {
    {BatchStatus::kFitted, "fitted"}, {BatchStatus::kMisfit, "misfit"}, {BatchStatus::kFailed, "failed"}};

struct BatchEntry {
  std::string beamid_version = kVersion;
  std::string campaign;           // the campaign folder, absolute
  std::string campaign_name;      // its campaign.json's name ("" when it could not be read)
  BatchStatus status = BatchStatus::kFailed;
  int exit_code = 0;              // of `beamid identify` (hb/errors.h: 0, 2, 3, 4, 5)
  std::string message;            // the verdict, or the error the program gave
  double seconds = 0.0;           // the campaign's wall time, identify and report
  std::string result_file;        // relative to the entry's folder; "" when none
  std::string report_file;        // relative to the entry's folder; "" when none
  std::string report_problem;     // why there is no report ("" when there is one or none was asked)
  std::string errors_file;        // what the program wrote on stderr, relative to the entry's folder
};

inline constexpr std::string_view kBatchEntryFormat = "beamid-batch-entry/1";
inline constexpr std::string_view kBatchEntryFileName = "batch.json";

std::vector<schema::FieldDoc> BatchEntryFields();
// `source` names the text in messages (the file it came from).
BatchEntry BatchEntryFromJson(const std::string& text, const std::string& source);
void WriteBatchEntry(const std::filesystem::path& file, const BatchEntry& entry);
BatchEntry ReadBatchEntry(const std::filesystem::path& file);

}  // namespace beamid::workflow
