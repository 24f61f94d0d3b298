// Another program of the machine (gnuplot, Chromium) run by beamid: the
// program and an argument vector go to posix_spawn, never to a shell, so no
// argument (a path, a label) is ever parsed as a command. Standard input is
// given text or /dev/null; standard output and error go to files or are
// discarded; every other file descriptor is closed in the child.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace beamid::solver {

struct ExternalProgram {
  std::string program;                 // a name looked up on PATH, or a path
  std::vector<std::string> arguments;  // argv[1], argv[2], ...: each passed as it is
  std::string debian_package;          // named when the program is missing
  std::optional<std::string> stdin_text;             // else standard input reads /dev/null
  std::optional<std::filesystem::path> stdout_file;  // created or truncated; else discarded
  std::optional<std::filesystem::path> stderr_file;  // created or truncated; else discarded
  double timeout_s = 0.0;  // > 0: the program is killed after this long (a hung browser)
};

// Runs the program and waits for it. Returns its exit status (0-255), or 128
// + the number of the signal that ended it. Throws EnvironmentError when the
// program is missing (naming its Debian package), cannot be started, an
// output file cannot be opened, or the timeout passed (the program killed).
int RunExternalProgram(const ExternalProgram& run);

}  // namespace beamid::solver
