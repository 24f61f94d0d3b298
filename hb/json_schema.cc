#include "hb/json_schema.h"

namespace beamid::schema {

std::string FieldTable(const std::vector<FieldDoc>& fields) {
  // A '|' inside a cell would end it.
  const auto cell = [](std::string text) {
    for (std::size_t at = text.find('|'); at != std::string::npos; at = text.find('|', at + 2)) text.replace(at, 1, "\\|");
    return text;
  };
  std::string table = "| field | type | unit | range | required |\n|---|---|---|---|---|\n";
  for (const FieldDoc& f : fields)
    table += fmt::format("| `{}` | {} | {} | {} | {} |\n", f.path, cell(f.type), f.unit.empty() ? "–" : f.unit,
                         cell(f.range), f.type == "rule" ? "" : f.optional ? "no" : "yes");
  return table;
}

}  // namespace beamid::schema
