// Small text helpers for messages and files.
// Text from a recording reaches messages, and through them the phasors file
// (a skipped step's reason) and the reports: it must be short, printable and
// valid UTF-8 there whatever the file held (a NUL would cut the message, a
// Latin-1 byte would make the JSON writer throw, a 1 GB line would become a
// 1 GB message). Excerpt makes it so; IsValidUtf8 tells whether a header
// cell may be kept as written.
#pragma once

#include <cstddef>
#include <cstdio>
#include <string>
#include <string_view>

namespace beamid::signal::internal {

// Shortest round-trip-ish representation (%.10g) for messages.
inline std::string FormatNumber(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.10g", value);
  return buffer;
}

// True when `text` is well-formed UTF-8 (no overlong forms, surrogates or
// code points beyond U+10FFFF).
bool IsValidUtf8(std::string_view text);

// `text` with ASCII letters in lower case (headers and unit spellings are
// compared so).
std::string Lowercase(std::string_view text);

// At most `max_chars` characters of `text` for a message: valid UTF-8 that
// is printable, control characters and bytes that are not UTF-8 written as
// \xNN (a tab as \t), and a longer text cut with "… (N bytes)".
std::string Excerpt(std::string_view text, std::size_t max_chars = 40);

}  // namespace beamid::signal::internal
