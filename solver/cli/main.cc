#include <algorithm>
#include <cstdio>
#include <exception>
#include <stdexcept>

#include <fmt/core.h>

#include "solver/cli/command_registry.h"

namespace beamid::cli {
std::vector<CommandEntry>& CommandRegistry() {
  static std::vector<CommandEntry> registry;
  return registry;
}
}  // namespace beamid::cli

int main(int argc, char** argv) {
  using namespace beamid::cli;
  CLI::App app{
      "beamid: identify the nonlinear support of a vibrating beam from stepped-sine tests.\n"
      "Run 'beamid COMMAND --help' for the options and an example of each command."};
  app.require_subcommand(1);
  GlobalOptions global;
  app.add_flag("-q,--quiet", global.quiet, "No progress output on stderr");
  auto& registry = CommandRegistry();
  std::sort(registry.begin(), registry.end(),
            [](const CommandEntry& a, const CommandEntry& b) { return a.name < b.name; });
  for (const auto& entry : registry) entry.setup(app, global);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  } catch (const std::invalid_argument& e) {
    fmt::print(stderr, "beamid: error: {}\n", e.what());
    return kExitBadInput;
  } catch (const std::runtime_error& e) {
    fmt::print(stderr, "beamid: failed: {}\n", e.what());
    return kExitNoConvergence;
  } catch (const std::exception& e) {
    fmt::print(stderr, "beamid: internal error: {}\n", e.what());
    return 1;
  }
  return 0;
}
