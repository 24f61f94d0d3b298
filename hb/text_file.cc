#include "hb/text_file.h"

#include <fstream>
#include <iterator>
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

std::string ReadTextFile(const std::filesystem::path& path, std::string_view what, std::string_view fix) {
  const auto fail = [&](const std::string& reason) {
    throw InputError(path.string(), "", "cannot read the " + std::string(what) + " (" + reason + ")", std::string(fix));
  };
  std::error_code error;
  const std::filesystem::file_status status = std::filesystem::status(path, error);
  if (!std::filesystem::exists(status)) fail("no such file");
  if (std::filesystem::is_directory(status)) fail("it is a folder, not a file");
  const std::uintmax_t size = std::filesystem::file_size(path, error);
  if (!error && size > kMaxInputFileBytes) fail("larger than 1 GiB");
  std::ifstream in(path, std::ios::binary);
  if (!in) fail("no read permission");
  std::string text;
  if (!error) text.reserve(static_cast<std::size_t>(size));
  text.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  if (in.bad()) fail("the read failed");
  return text;
}

}  // namespace beamid
