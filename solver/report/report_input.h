// What `beamid report` reads: a result.json of `beamid identify` (format
// "beamid-result/1") or a diagnosis.json of `beamid diagnose`, which is
// recognised by its keys "selected", "candidates", "location", "summary" and
// carries its result either embedded ("result": {...}) or as a path
// ("result": "path" or "result_file": "path", relative to the diagnosis
// file). The campaign is --campaign when given, else result.json's
// campaign.folder: as written when it exists from the working folder,
// otherwise relative to the result file's folder, otherwise
// campaign.absolute_folder (written by `beamid identify`).
#pragma once

#include <filesystem>
#include <optional>
#include <string>

#include "solver/diagnosis/diagnosis_io.h"
#include "solver/estimation/result_file.h"

namespace beamid::solver {

struct ReportInput {
  std::filesystem::path input_file;   // as given
  std::filesystem::path result_file;  // the result.json (the input file when it holds the result embedded)
  ResultFile result;                  // read by solver/estimation/result_io.h
  std::optional<DiagnosisFile> diagnosis;  // when the input is a diagnosis
  std::filesystem::path campaign_folder;
};

// Throws std::invalid_argument naming the file and what to fix.
ReportInput LoadReportInput(const std::filesystem::path& input_file,
                            const std::optional<std::filesystem::path>& campaign_folder = std::nullopt);

}  // namespace beamid::solver
