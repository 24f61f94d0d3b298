// One cell of a CSV table beamid writes for spreadsheets (RFC 4180): a
// number that is not finite is an empty cell, never "inf" or "nan", which a
// reader would take for a value; a text holding a comma, a quote or a line
// break is quoted, its quotes doubled, so that a label like "1,5 N" stays
// one cell.
#pragma once

#include <string>
#include <string_view>

namespace beamid::hb {

// `value` in `format` (a fmt format for one number), or "" when it is not finite.
std::string CsvNumber(double value, std::string_view format);

// `text` as one cell.
std::string CsvText(std::string_view text);

}  // namespace beamid::hb
