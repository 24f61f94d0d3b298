// Splitting a written CSV text for tests that check its header and rows
// against the struct it was written from: lines, comma-separated cells (a
// trailing comma is an empty last cell), and a number as the writers print
// it (9 significant digits).
#pragma once

#include <algorithm>
#include <filesystem>
#include <fstream>
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

// The numbers of a written CSV file by column (time_s first), its header
// line skipped: as many columns as the header has cells.
inline std::vector<std::vector<double>> ReadCsvColumns(const std::filesystem::path& file) {
  std::ifstream in(file);
  std::string line;
  std::getline(in, line);
  const size_t columns = static_cast<size_t>(std::count(line.begin(), line.end(), ',')) + 1;
  std::vector<std::vector<double>> out(columns);
  while (std::getline(in, line)) {
    std::istringstream row(line);
    std::string cell;
    for (size_t c = 0; c < columns && std::getline(row, cell, ','); ++c) out[c].push_back(std::stod(cell));
  }
  return out;
}

// The header line of a written CSV file.
inline std::string ReadCsvHeader(const std::filesystem::path& file) {
  std::ifstream in(file);
  std::string line;
  std::getline(in, line);
  return line;
}

}  // namespace beamid::testing
