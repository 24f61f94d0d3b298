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
#include <string_view>

namespace beamid {

void WriteTextFileAtomically(const std::filesystem::path& path, std::string_view text);

}  // namespace beamid
