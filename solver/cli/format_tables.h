// Every JSON format beamid writes and reads, with the table of its fields
// that its declaration gives (hb/json_schema.h): what `beamid formats`
// prints and docs/formats.md holds.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "hb/json_schema.h"

namespace beamid::cli {

struct DocumentedFormat {
  std::string tag;    // the file's "format" field, e.g. "beamid-frc/1"
  std::string title;  // what the file is, for a heading
  std::function<std::vector<schema::FieldDoc>()> fields;
};

const std::vector<DocumentedFormat>& DocumentedFormats();

}  // namespace beamid::cli
