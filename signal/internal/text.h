// Small text helpers for messages and files.
#pragma once

#include <cstdio>
#include <string>

namespace beamid::signal::internal {

// Shortest round-trip-ish representation (%.10g) for messages.
inline std::string FormatNumber(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.10g", value);
  return buffer;
}

}  // namespace beamid::signal::internal
