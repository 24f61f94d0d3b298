// The beamid program is a set of subcommands, one per file in solver/cli/.
// Each file registers itself with BEAMID_REGISTER_COMMAND, so adding a command
// never touches main.cc. Exit codes (hb/errors.h, mapped in main.cc): 0
// success, 1 internal error, 2 bad input (the user can fix it), 3 a numerical
// failure (no convergence), 4 the environment (missing program, disk, fork,
// memory), 5 fitted, but the model misses the data beyond their noise (the
// result is written).
#pragma once

#include <functional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "hb/errors.h"

namespace beamid::cli {

// Options every subcommand understands (before or after its name).
struct GlobalOptions {
  bool quiet = false;             // no progress and no summary, only errors
  std::string progress = "text";  // "json": one JSON object per line on stderr (solver/cli/cli_output.h)

  bool JsonProgress() const { return progress == "json"; }
};

using CommandSetup = std::function<void(CLI::App& app, const GlobalOptions& global)>;

struct CommandEntry {
  std::string name;
  CommandSetup setup;
};

std::vector<CommandEntry>& CommandRegistry();

inline bool RegisterCommand(std::string name, CommandSetup setup) {
  CommandRegistry().push_back({std::move(name), std::move(setup)});
  return true;
}

}  // namespace beamid::cli

#define BEAMID_CONCAT_INNER(a, b) a##b
#define BEAMID_CONCAT(a, b) BEAMID_CONCAT_INNER(a, b)
#define BEAMID_REGISTER_COMMAND(name, setup) \
  static const bool BEAMID_CONCAT(beamid_command_registered_, __COUNTER__) = ::beamid::cli::RegisterCommand(name, setup)
