// Range checks for the options structs' Validate() (every folder uses them):
// one wording, "<Struct>.<field> = <value>: must be <allowed>", so that a
// library user is told the same as the command line, and a NaN fails every
// check instead of slipping through a comparison.
#pragma once

#include <charconv>
#include <cmath>
#include <string>
#include <string_view>
#include <system_error>

#include "hb/errors.h"

namespace beamid::option_checks {

// The shortest text that reads back as the same double, so that 1e-07 is not
// shown as 0.000000.
inline std::string FormatValue(double value) {
  char buffer[32];
  const auto [end, error] = std::to_chars(buffer, buffer + sizeof buffer, value);
  return error == std::errc() ? std::string(buffer, end) : std::to_string(value);
}
inline std::string FormatValue(int value) { return std::to_string(value); }

[[noreturn]] inline void Refuse(std::string_view field, const std::string& value, std::string_view allowed) {
  throw InputError(std::string(field) + " = " + value + ": must be " + std::string(allowed));
}

// min ≤ value ≤ max.
inline void RequireInRange(std::string_view field, int value, int min, int max) {
  if (value < min || value > max) Refuse(field, FormatValue(value), FormatValue(min) + " … " + FormatValue(max));
}

inline void RequireAtLeast(std::string_view field, int value, int min) {
  if (value < min) Refuse(field, FormatValue(value), "at least " + FormatValue(min));
}

// min ≤ value ≤ max (finite).
inline void RequireInRange(std::string_view field, double value, double min, double max) {
  if (!(value >= min && value <= max)) Refuse(field, FormatValue(value), FormatValue(min) + " … " + FormatValue(max));
}

// min < value, finite.
inline void RequireAbove(std::string_view field, double value, double min) {
  if (!(value > min && std::isfinite(value)))
    Refuse(field, FormatValue(value), "a finite number above " + FormatValue(min));
}

// min ≤ value, finite.
inline void RequireAtLeast(std::string_view field, double value, double min) {
  if (!(value >= min && std::isfinite(value)))
    Refuse(field, FormatValue(value), "a finite number of at least " + FormatValue(min));
}

inline void RequirePositive(std::string_view field, double value) { RequireAbove(field, value, 0.0); }
inline void RequireNonNegative(std::string_view field, double value) { RequireAtLeast(field, value, 0.0); }

// The most harmonics a model or an estimator takes: the limit the command
// line and the readers state (docs/architecture.md, "What the readers
// guarantee"), so that a library call cannot start work the program refuses.
inline constexpr int kMaxHarmonics = 50;

}  // namespace beamid::option_checks
