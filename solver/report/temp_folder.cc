#include "solver/report/temp_folder.h"

#include <stdlib.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>
#include <vector>

#include "hb/errors.h"

namespace beamid::solver {

namespace fs = std::filesystem;

TempFolder::TempFolder(const std::string& purpose) {
  std::error_code error;
  fs::path base = fs::temp_directory_path(error);
  if (error) base = "/tmp";
  const std::string pattern = (base / ("beamid_" + purpose + "_XXXXXX")).string();
  std::vector<char> name(pattern.begin(), pattern.end());
  name.push_back('\0');
  if (::mkdtemp(name.data()) == nullptr)
    throw EnvironmentError("cannot create a temporary folder in " + base.string() + ": " + std::strerror(errno) +
                           " (set TMPDIR to a writable folder)");
  path_ = name.data();
}

TempFolder::~TempFolder() {
  std::error_code error;
  fs::remove_all(path_, error);
}

std::string ReadWholeFile(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

}  // namespace beamid::solver
