#include "hb/text_file.h"

#include <fstream>
#include <string>
#include <system_error>

#include <unistd.h>

#include "hb/errors.h"

namespace beamid {

void WriteTextFileAtomically(const std::filesystem::path& path, std::string_view text) {
  std::filesystem::path temporary = path;
  temporary += ".partial-" + std::to_string(::getpid());
  std::error_code error;
  {
    std::ofstream out(temporary, std::ios::binary);
    if (!out) throw InputError(path.string() + ": cannot write this file (check the folder and permissions)");
    out.write(text.data(), static_cast<std::streamsize>(text.size()));
    out.flush();
    if (!out) {
      out.close();
      std::filesystem::remove(temporary, error);
      throw EnvironmentError(path.string() + ": writing failed (disk full?)");
    }
  }
  std::filesystem::rename(temporary, path, error);
  if (error) {
    std::filesystem::remove(temporary, error);
    throw InputError(path.string() + ": cannot replace this file (is it a folder, or read-only?)");
  }
}

}  // namespace beamid
