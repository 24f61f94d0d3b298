// beamid formats [TAG]: the fields of the JSON files beamid writes and
// reads, as Markdown tables (docs/formats.md holds the same tables).
#include <memory>
#include <string>

#include <fmt/format.h>

#include "hb/errors.h"
#include "solver/cli/command_registry.h"
#include "solver/cli/format_tables.h"

namespace beamid::cli {
namespace {

void RunFormats(const std::string& tag) {
  std::string known;
  for (const DocumentedFormat& f : DocumentedFormats()) {
    if (tag.empty()) {
      fmt::print("## {} (format \"{}\")\n\n{}\n", f.title, f.tag, schema::FieldTable(f.fields()));
    } else if (f.tag == tag) {
      fmt::print("{}", schema::FieldTable(f.fields()));
      return;
    }
    known += (known.empty() ? "" : ", ") + f.tag;
  }
  if (!tag.empty())
    throw InputError("formats: no format \"" + tag + "\". Fix: give one of " + known + ", or none for all");
}

BEAMID_REGISTER_COMMAND("formats", [](CLI::App& app, const GlobalOptions&) {
  auto tag = std::make_shared<std::string>();
  CLI::App* sub = app.add_subcommand(
      "formats",
      "Print the fields of the JSON files beamid writes and reads (path, type, unit, range, required).\n"
      "Example: beamid formats beamid-frc/1");
  sub->add_option("format", *tag, "One format's tag (its \"format\" field); all formats when left out");
  sub->callback([tag] { RunFormats(*tag); });
});

}  // namespace
}  // namespace beamid::cli
