// A private temporary folder (mode 0700, a fresh name from mkdtemp) for the
// files an external program reads or writes (gnuplot's SVG, Chromium's
// profile); it and everything in it are removed when the object goes.
#pragma once

#include <filesystem>
#include <string>

namespace beamid::solver {

class TempFolder {
 public:
  // `purpose` is part of the folder's name (beamid_<purpose>_XXXXXX), so a
  // folder left by a killed run tells what made it. Throws EnvironmentError
  // when the temporary directory refuses a new folder.
  explicit TempFolder(const std::string& purpose);
  ~TempFolder();
  TempFolder(const TempFolder&) = delete;
  TempFolder& operator=(const TempFolder&) = delete;

  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

// The whole of a file (what an external program wrote, a page to lay out);
// "" when it is missing or unreadable, which the caller's own check reports.
std::string ReadWholeFile(const std::filesystem::path& path);

}  // namespace beamid::solver
