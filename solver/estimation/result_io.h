// The one reader and writer of result.json (format "beamid-result/1",
// docs/result-format.md): a ResultFile (solver/estimation/result_file.h) to
// JSON text and back. The writer keeps the keys every earlier beamid wrote,
// adds "beamid_version", and writes the held-out channels, quality entries
// and parameters in the struct's order. JSON has no NaN: a number that is not
// finite is written as null and read back as NaN.
// One declaration of its fields (result_io.cc, hb/json_schema.h) drives the
// writer, the reader and the field table of docs/formats.md. Reading checks
// every field and its range, refuses a key it does not declare, and throws
// InputError naming the file, the field (e.g. "fit.starts[2].objective") and
// the fix; fields later versions added ("beamid_version",
// "campaign.absolute_folder", "campaign_sha256", "model.kind",
// "model.beam.loss_factor", "validation", the verdict) may be absent.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "hb/json_schema.h"

#include "solver/estimation/result_file.h"

namespace beamid::solver {

// The fields of the file: path, type, unit, range (docs/formats.md).
std::vector<schema::FieldDoc> ResultFileFields();

std::string ResultFileToJson(const ResultFile& result);
// `source` names the text in messages (the file it came from).
ResultFile ResultFileFromJson(const std::string& text, const std::string& source);

// Atomically (hb/text_file.h): the old file or the new one, never half.
void WriteResultFile(const std::filesystem::path& file, const ResultFile& result);
ResultFile ReadResultFile(const std::filesystem::path& file);

}  // namespace beamid::solver
