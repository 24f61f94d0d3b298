#include <algorithm>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <new>
#include <stdexcept>
#include <system_error>

#include <fmt/core.h>
#include <nlohmann/json.hpp>

#include "hb/version.h"
#include "solver/cli/cli_output.h"
#include "solver/cli/command_registry.h"

namespace beamid::cli {
std::vector<CommandEntry>& CommandRegistry() {
  static std::vector<CommandEntry> registry;
  return registry;
}
}  // namespace beamid::cli

int main(int argc, char** argv) {
  using namespace beamid;
  using namespace beamid::cli;
  CLI::App app{
      "beamid: identify the nonlinear support of a vibrating beam from stepped-sine tests.\n"
      "Run 'beamid COMMAND --help' for the options and an example of each command.\n"
      "Exit codes: 0 success, 2 bad input (the message says what to fix), 3 failure to converge,\n"
      "4 environment (a missing program, a full disk, too little memory), 1 internal error."};
  app.set_version_flag("--version", std::string("beamid ") + kVersion);
  app.require_subcommand(1);
  // --quiet and --progress may also follow the command's name.
  app.fallthrough();
  GlobalOptions global;
  app.add_flag("-q,--quiet", global.quiet, "No progress and no summary on the terminal, only errors");
  app.add_option("--progress", global.progress,
                 "Progress format: text (terminal) or json (one JSON object per line on stderr, for programs)")
      ->check(CLI::IsMember({"text", "json"}))
      ->capture_default_str();
  auto& registry = CommandRegistry();
  std::sort(registry.begin(), registry.end(),
            [](const CommandEntry& a, const CommandEntry& b) { return a.name < b.name; });
  for (const auto& entry : registry) entry.setup(app, global);
  for (CLI::App* command : app.get_subcommands([](CLI::App*) { return true; }))
    command->footer(
        "Global options (before or after the command's name):\n"
        "  -q,--quiet                  No progress and no summary on the terminal, only errors\n"
        "  --progress text|json        json: one JSON object per line on stderr ({\"event\": \"progress\", ...},\n"
        "                              {\"event\": \"done\", ...}, last {\"event\": \"exit\", \"exit_code\": N, ...})\n"
        "Exit codes: 0 success, 2 bad input, 3 failure to converge, 4 environment, 5 fitted but the model misses\n"
        "the data beyond their noise (the result is written; run beamid diagnose), 1 internal error.");
  // With --progress json, stderr holds JSON lines only: the error goes into
  // the last one.
  // The exit code stands whether or not the message can be written (a full
  // or closed stderr): printing the error must not become a crash.
  auto fail = [&](int code, const std::string& prefix, const std::string& message) noexcept {
    try {
      if (global.JsonProgress())
        PrintJsonExit(code, message);
      else
        PrintToStderr("beamid: " + prefix + ": " + message + "\n");
    } catch (...) {
    }
    return code;
  };
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    // A mistyped command line is bad input like a bad file.
    if (global.JsonProgress()) return fail(kExitBadInput, "error", e.what());
    app.exit(e);
    return kExitBadInput;
  } catch (const std::invalid_argument& e) {  // beamid::InputError and the readers' older throws
    return fail(kExitBadInput, "error", e.what());
  } catch (const nlohmann::json::exception& e) {
    // A JSON value a reader did not check (a number beyond double's range,
    // a wrong type): the input's, not beamid's, fault.
    return fail(kExitBadInput, "error", std::string("a JSON input holds a value beamid cannot use: ") + e.what());
  } catch (const NumericalError& e) {
    return fail(kExitNoConvergence, "failed", e.what());
  } catch (const ModelMissesData& e) {
    return fail(kExitModelMissesData, "misfit", e.what());
  } catch (const EnvironmentError& e) {
    return fail(kExitEnvironment, "environment", e.what());
  } catch (const std::filesystem::filesystem_error& e) {
    return fail(kExitEnvironment, "environment", e.what());
  } catch (const std::system_error& e) {
    // Writing the summary to a full or closed stdout, starting a thread.
    return fail(kExitEnvironment, "environment", e.what());
  } catch (const std::bad_alloc&) {
    return fail(kExitEnvironment, "environment",
                "not enough memory for this problem: use fewer steps, harmonics or samples");
  } catch (const std::exception& e) {
    return fail(kExitInternalError, "internal error", std::string(e.what()) + " (please report this as a bug)");
  }
  if (global.JsonProgress()) PrintJsonExit(0, "");
  return 0;
}
