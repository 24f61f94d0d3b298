// Splitting a written CSV text for tests that check its header and rows
// against the struct it was written from: lines, comma-separated cells (a
// trailing comma is an empty last cell), and a number as the writers print
// it (9 significant digits).
#pragma once

#include <sstream>
#include <string>
#include <vector>

#include <fmt/core.h>

namespace beamid::testing {

inline std::vector<std::string> Lines(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) out.push_back(line);
  return out;
}

inline std::vector<std::string> Cells(const std::string& line) {
  std::vector<std::string> out;
  std::istringstream in(line);
  for (std::string cell; std::getline(in, cell, ',');) out.push_back(cell);
  if (!line.empty() && line.back() == ',') out.push_back("");
  return out;
}

inline std::string G9(double v) { return fmt::format("{:.9g}", v); }

}  // namespace beamid::testing
