// Reading and writing the files a user names.
// Writes a whole text file or nothing: the text goes to a temporary name in
// the same folder, which is renamed to the final path once it is complete
// (rename is atomic within one file system). A run killed halfway, or a disk
// that fills, leaves the previous file or none, never a truncated one that a
// reader would take for complete. Every writer of beamid uses it.
// Throws InputError when the path cannot be written (missing folder, no
// permission, a folder of that name) and EnvironmentError when writing fails
// (disk full).
#pragma once

#include <filesystem>
#include <cstdint>
#include <string>
#include <string_view>

namespace beamid {

void WriteTextFileAtomically(const std::filesystem::path& path, std::string_view text);

// Reads a whole file that a user named. Throws InputError "<path>: cannot
// read the <what> (<reason>). Fix: <fix>" when it is missing, a folder, not
// readable, or larger than kMaxInputFileBytes (no file of a stepped-sine
// test is; a bigger one would exhaust memory before any check could speak).
inline constexpr std::uintmax_t kMaxInputFileBytes = std::uintmax_t{1} << 30;  // 1 GiB
std::string ReadTextFile(const std::filesystem::path& path, std::string_view what, std::string_view fix);

}  // namespace beamid
