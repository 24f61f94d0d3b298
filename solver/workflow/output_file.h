// An output file of a workflow: written whole or not at all (hb/text_file.h),
// its folder created first. The paths were checked before any work
// (solver/workflow/output_paths.h).
#pragma once

#include <filesystem>
#include <string>

namespace beamid::workflow {

// Writes text to a file, creating its folder; throws std::invalid_argument
// naming the path if it cannot.
void WriteTextFile(const std::filesystem::path& path, const std::string& text);

}  // namespace beamid::workflow
