#include "hb/file_stem.h"

#include <fmt/core.h>

namespace beamid::hb {

std::string FileStem(const std::string& text, const std::string& prefix) {
  std::string stem;
  for (const char c : text) {
    const bool plain = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '-' ||
                       c == '_' || c == '.';
    stem += plain ? c : '_';
  }
  if (stem.empty() || stem.front() == '.' || stem.front() == '-') stem.insert(0, prefix);
  return stem.substr(0, 120);
}

std::string UniqueFileStem(const std::string& text, const std::string& prefix, std::set<std::string>& taken) {
  const std::string stem = FileStem(text, prefix);
  std::string name = stem;
  for (int copy = 2; taken.count(name); ++copy) name = fmt::format("{}-{}", stem, copy);
  taken.insert(name);
  return name;
}

}  // namespace beamid::hb
