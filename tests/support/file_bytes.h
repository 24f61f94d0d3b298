// A file's bytes read or written whole, and what a run of the beamid program
// left: the helpers of the tests that run the real program on files they
// spoil (bad input, injection, data safety).
#pragma once

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace beamid::testing {

inline std::string ReadFile(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

inline void WriteFile(const std::filesystem::path& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

struct ProgramRun {
  int exit_code = -1;
  std::string output;  // standard output, then standard error
};

}  // namespace beamid::testing
