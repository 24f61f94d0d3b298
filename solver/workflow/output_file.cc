#include "solver/workflow/output_file.h"

#include <system_error>

#include "hb/text_file.h"

namespace beamid::workflow {

void WriteTextFile(const std::filesystem::path& path, const std::string& text) {
  std::error_code error;
  if (path.has_parent_path()) std::filesystem::create_directories(path.parent_path(), error);
  WriteTextFileAtomically(path, text);
}

}  // namespace beamid::workflow
