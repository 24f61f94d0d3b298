// docs/formats.md holds, for every JSON format beamid writes and reads, the
// table of its fields that the format's declaration (hb/json_schema.h)
// gives: path, type, unit, range, required. The documentation cannot drift
// from the reader: a field added, renamed or given another range changes the
// table, and this test then fails; `beamid formats TAG` prints the table the
// document must hold.
#include <fstream>
#include <functional>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "hb/json_schema.h"
#include "solver/cli/format_tables.h"

namespace beamid {
namespace {

std::string Documentation() {
  std::ifstream in("docs/formats.md");
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// The table between "<!-- fields: TAG -->" and "<!-- end fields -->".
std::string DocumentedTable(const std::string& doc, const std::string& tag) {
  const std::string open = "<!-- fields: " + tag + " -->\n";
  const std::size_t start = doc.find(open);
  if (start == std::string::npos) return "(no section)";
  const std::size_t end = doc.find("<!-- end fields -->", start);
  if (end == std::string::npos) return "(section not closed)";
  return doc.substr(start + open.size(), end - start - open.size());
}

TEST(FormatDocs, EveryFormatsFieldTableIsTheOneItsDeclarationGives) {
  const std::string doc = Documentation();
  ASSERT_FALSE(doc.empty()) << "docs/formats.md is missing (the test runs from the source folder)";
  for (const cli::DocumentedFormat& f : cli::DocumentedFormats())
    EXPECT_EQ(DocumentedTable(doc, f.tag), schema::FieldTable(f.fields()))
        << "docs/formats.md: the section <!-- fields: " << f.tag << " --> must hold what `beamid formats " << f.tag
        << "` prints";
}

}  // namespace
}  // namespace beamid
