// The numbers the documentation quotes from the examples are the examples'
// own: the suite runs examples/paper_setup/run.sh ("demo") and
// examples/concealed_friction/run.sh ("friction") with the built program, then
// reads every marker
//   <!-- check EXAMPLE FILE POINTER [over POINTER] [times FACTOR] [count] (rel TOL | abs TOL) -->NUMBER
//   <!-- check EXAMPLE FILE POINTER -->TEXT
// in README.md, docs/*.md and examples/*/README.md and compares the quoted
// number (or text) with the value at the JSON pointer in that example's
// output file: value = file[POINTER] (/ file[over POINTER]) (× FACTOR), or
// the size of the array there with `count`; |quoted − value| ≤ TOL·|value|
// (rel) or ≤ TOL (abs). A quoted text must begin with the string there. So a
// change that moves a quoted number fails here until the text is updated.
// The suite also checks that every relative link of those files resolves to
// a file (and a heading, for an anchor into a Markdown file), and that the
// first-harmonic tables the README shows give a measured backbone.
#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <optional>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <fmt/core.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "solver/report/external_program.h"
#include "tests/support/temp_path.h"

namespace beamid {
namespace {

namespace fs = std::filesystem;

std::string ReadText(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// The Markdown files whose quoted numbers and links are checked.
std::vector<fs::path> DocumentationFiles() {
  std::vector<fs::path> files = {"README.md"};
  for (const auto& entry : fs::directory_iterator("docs"))
    if (entry.path().extension() == ".md") files.push_back(entry.path());
  for (const auto& entry : fs::directory_iterator("examples"))
    if (fs::exists(entry.path() / "README.md")) files.push_back(entry.path() / "README.md");
  std::sort(files.begin(), files.end());
  return files;
}

// A number as the documentation writes it: "150.43", "−1.7·10⁴",
// "1.90·10⁻⁴", "3.9e-5". Returns the value and how many bytes it took.
std::optional<std::pair<double, std::size_t>> ParseQuotedNumber(const std::string& text) {
  static const std::string kMinus = "\u2212";
  static const std::string kDot = "\u00b7";
  static const std::string kSuperMinus = "\u207b";
  static const std::vector<std::string> kSuperDigits = {"\u2070", "\u00b9", "\u00b2", "\u00b3", "\u2074",
                                                        "\u2075", "\u2076", "\u2077", "\u2078", "\u2079"};
  std::size_t i = 0;
  std::string plain;
  if (text.compare(0, kMinus.size(), kMinus) == 0) {
    plain += '-';
    i += kMinus.size();
  } else if (i < text.size() && (text[i] == '-' || text[i] == '+')) {
    plain += text[i++];
  }
  const std::size_t digits_start = i;
  while (i < text.size() && (std::isdigit(static_cast<unsigned char>(text[i])) || text[i] == '.')) plain += text[i++];
  // A full stop after the number ends the sentence.
  if (i > digits_start && text[i - 1] == '.') {
    --i;
    plain.pop_back();
  }
  if (i == digits_start) return std::nullopt;
  double value = std::stod(plain);
  if (text.compare(i, kDot.size() + 2, kDot + "10") == 0) {
    std::size_t j = i + kDot.size() + 2;
    int sign = 1;
    if (text.compare(j, kSuperMinus.size(), kSuperMinus) == 0) {
      sign = -1;
      j += kSuperMinus.size();
    }
    int exponent = 0;
    bool any = false;
    for (bool more = true; more;) {
      more = false;
      for (int d = 0; d < 10; ++d) {
        if (text.compare(j, kSuperDigits[d].size(), kSuperDigits[d]) == 0) {
          exponent = exponent * 10 + d;
          j += kSuperDigits[d].size();
          any = more = true;
          break;
        }
      }
    }
    if (!any) return std::nullopt;
    value *= std::pow(10.0, sign * exponent);
    i = j;
  } else if (i + 1 < text.size() && (text[i] == 'e' || text[i] == 'E') &&
             (std::isdigit(static_cast<unsigned char>(text[i + 1])) || text[i + 1] == '-' || text[i + 1] == '+')) {
    std::size_t j = i + 1;
    std::string exponent(1, text[j++]);
    while (j < text.size() && std::isdigit(static_cast<unsigned char>(text[j]))) exponent += text[j++];
    value *= std::pow(10.0, std::stod(exponent));
    i = j;
  }
  return std::make_pair(value, i);
}

// One marker's comparison: what it quotes, what the example gave, whether
// they agree, in one line for the log.
struct Comparison {
  std::string where;  // file:line
  bool ok = false;
  std::string line;
};

// Where each example wrote its output ("demo" -> folder).
using ExampleFolders = std::vector<std::pair<std::string, fs::path>>;

std::optional<nlohmann::json> ReadJson(const fs::path& file, std::string* error) {
  if (!fs::exists(file)) {
    *error = "no file " + file.string();
    return std::nullopt;
  }
  try {
    return nlohmann::json::parse(ReadText(file));
  } catch (const nlohmann::json::exception& e) {
    *error = file.string() + " is no JSON: " + e.what();
    return std::nullopt;
  }
}

const nlohmann::json* At(const nlohmann::json& doc, const std::string& pointer, std::string* error) {
  try {
    const nlohmann::json::json_pointer p(pointer);
    if (!doc.contains(p)) {
      *error = "no " + pointer;
      return nullptr;
    }
    return &doc.at(p);
  } catch (const nlohmann::json::exception& e) {
    *error = "pointer " + pointer + ": " + e.what();
    return nullptr;
  }
}

// Every marker of one Markdown text, compared with the examples' outputs.
std::vector<Comparison> CheckMarkers(const std::string& text, const std::string& name, const ExampleFolders& examples) {
  static const std::regex kMarker(R"(<!-- check ([^>]*?) -->)");
  std::vector<Comparison> out;
  for (auto it = std::sregex_iterator(text.begin(), text.end(), kMarker); it != std::sregex_iterator(); ++it) {
    const std::size_t at = static_cast<std::size_t>(it->position(0));
    Comparison c;
    c.where = name + ":" + std::to_string(1 + std::count(text.begin(), text.begin() + at, '\n'));
    const std::string spec = (*it)[1];
    const std::string quoted_text = text.substr(at + it->length(0), 60);
    c.line = c.where + ": check " + spec + ": ";
    std::istringstream words(spec);
    std::string example, file, pointer, over, word;
    words >> example >> file >> pointer;
    double factor = 1.0, tolerance = -1.0;
    bool relative = false, count = false;
    bool bad_spec = pointer.empty();
    while (words >> word) {
      if (word == "over") {
        bad_spec |= !(words >> over);
      } else if (word == "times") {
        bad_spec |= !(words >> factor);
      } else if (word == "count") {
        count = true;
      } else if (word == "rel" || word == "abs") {
        relative = word == "rel";
        bad_spec |= !(words >> tolerance) || tolerance < 0;
      } else {
        bad_spec = true;
      }
    }
    const auto folder =
        std::find_if(examples.begin(), examples.end(), [&](const auto& e) { return e.first == example; });
    std::string error;
    std::optional<nlohmann::json> doc;
    const nlohmann::json* value = nullptr;
    if (bad_spec) {
      error = "malformed marker";
    } else if (folder == examples.end()) {
      error = "no example named '" + example + "'";
    } else if ((doc = ReadJson(folder->second / file, &error))) {
      value = At(*doc, pointer, &error);
    }
    if (value == nullptr) {
      c.line += "FAILED: " + error;
      out.push_back(c);
      continue;
    }
    if (value->is_string()) {
      // The name may be set in code or bold: `support_friction`, **support_friction**.
      const std::size_t start = text.find_first_not_of("`*", at + it->length(0));
      const std::string expected = value->get<std::string>();
      c.ok = start != std::string::npos && text.compare(start, expected.size(), expected) == 0;
      c.line += "\"" + expected + "\" against \"" + quoted_text.substr(0, quoted_text.find('\n')) + "\"" +
                (c.ok ? ": ok" : ": FAILED, the text must begin with it");
      out.push_back(c);
      continue;
    }
    const auto quoted = ParseQuotedNumber(quoted_text);
    double number = 0.0;
    if (count && value->is_array()) {
      number = static_cast<double>(value->size());
    } else if (!count && value->is_number()) {
      number = value->get<double>();
    } else {
      c.line += std::string("FAILED: the value at ") + pointer + " is " + value->dump().substr(0, 40) +
                (count ? ", not an array" : ", not a number");
      out.push_back(c);
      continue;
    }
    if (!over.empty()) {
      const nlohmann::json* denominator = At(*doc, over, &error);
      if (denominator == nullptr || !denominator->is_number()) {
        c.line += "FAILED: " + (denominator == nullptr ? error : over + " is not a number");
        out.push_back(c);
        continue;
      }
      number /= denominator->get<double>();
    }
    number *= factor;
    if (tolerance < 0 || !quoted) {
      c.line += !quoted ? "FAILED: no number after the marker (\"" + quoted_text.substr(0, 20) + "\")"
                        : "FAILED: the marker states no tolerance (rel TOL or abs TOL)";
      out.push_back(c);
      continue;
    }
    const double allowed = relative ? tolerance * std::abs(number) : tolerance;
    const double difference = std::abs(quoted->first - number);
    c.ok = difference <= allowed;
    std::ostringstream line;
    line.precision(8);
    line << "quoted " << quoted_text.substr(0, quoted->second) << " = " << quoted->first << ", the example gives "
         << number << " (difference " << difference << ", allowed " << allowed << ")"
         << (c.ok ? ": ok" : ": FAILED, update the text");
    c.line += line.str();
    out.push_back(c);
  }
  return out;
}

// GitHub's anchor of a heading: lower case, punctuation dropped, spaces to '-'.
std::string Anchor(const std::string& heading) {
  std::string anchor;
  for (const char ch : heading) {
    const auto u = static_cast<unsigned char>(ch);
    if (u >= 0x80 || std::isalnum(u) || ch == '-' || ch == '_')
      anchor += static_cast<char>(std::tolower(u));
    else if (ch == ' ')
      anchor += '-';
  }
  return anchor;
}

std::set<std::string> Anchors(const std::string& markdown) {
  std::set<std::string> anchors;
  std::istringstream lines(markdown);
  bool in_code = false;
  for (std::string line; std::getline(lines, line);) {
    if (line.rfind("```", 0) == 0) in_code = !in_code;
    if (in_code || line.empty() || line[0] != '#') continue;
    const std::size_t text = line.find_first_not_of('#');
    if (text == std::string::npos || line[text] != ' ') continue;
    anchors.insert(Anchor(line.substr(text + 1)));
  }
  return anchors;
}

// The relative links of a Markdown file that lead nowhere.
std::vector<std::string> BrokenLinks(const fs::path& file) {
  static const std::regex kLink(R"(\]\(([^)\s]+)\))");
  const std::string text = ReadText(file);
  std::vector<std::string> broken;
  for (auto it = std::sregex_iterator(text.begin(), text.end(), kLink); it != std::sregex_iterator(); ++it) {
    const std::string target = (*it)[1];
    // Mathematics such as "E[Δχ²](x)" is no link: a link names a file or an anchor.
    if (target.find_first_of("./#") == std::string::npos) continue;
    if (target.find("://") != std::string::npos || target.rfind("mailto:", 0) == 0) continue;
    const std::size_t hash = target.find('#');
    const std::string path = target.substr(0, hash);
    const fs::path resolved = path.empty() ? file : file.parent_path() / path;
    if (!fs::exists(resolved)) {
      broken.push_back(file.string() + ": " + target + " (no " + resolved.string() + ")");
    } else if (hash != std::string::npos && resolved.extension() == ".md" &&
               Anchors(ReadText(resolved)).count(target.substr(hash + 1)) == 0) {
      broken.push_back(file.string() + ": " + target + " (no such heading in " + resolved.string() + ")");
    }
  }
  return broken;
}

struct ScriptRun {
  int exit_code = -1;
  fs::path log;
};

ScriptRun RunExample(const std::string& script, const fs::path& output) {
  ScriptRun run;
  run.log = output.string() + ".log";
  solver::ExternalProgram program;
  program.program = "bash";
  program.arguments = {script, output.string(), BEAMID_EXECUTABLE};
  program.debian_package = "bash";
  program.stdout_file = run.log;
  program.stderr_file = output.string() + ".stderr.log";
  program.timeout_s = 1200.0;
  run.exit_code = solver::RunExternalProgram(program);
  // One log, stdout then stderr, for the failure message.
  std::ofstream(run.log, std::ios::app) << ReadText(output.string() + ".stderr.log");
  return run;
}

std::string Tail(const fs::path& log, std::size_t chars = 3000) {
  const std::string text = ReadText(log);
  return text.size() > chars ? text.substr(text.size() - chars) : text;
}

class ReadmeNumbers : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    folder_ = new fs::path(testing::UniqueTempPath("beamid_readme_numbers"));
    fs::remove_all(*folder_);
    fs::create_directories(*folder_);
    examples_ = new ExampleFolders{{"demo", *folder_ / "demo"}, {"friction", *folder_ / "friction"}};
    runs_ = new std::vector<ScriptRun>{RunExample("examples/paper_setup/run.sh", *folder_ / "demo"),
                                       RunExample("examples/concealed_friction/run.sh", *folder_ / "friction")};
  }
  static void TearDownTestSuite() {
    fs::remove_all(*folder_);
    delete runs_;
    delete examples_;
    delete folder_;
  }
  static fs::path* folder_;
  static ExampleFolders* examples_;
  static std::vector<ScriptRun>* runs_;
};

fs::path* ReadmeNumbers::folder_ = nullptr;
ExampleFolders* ReadmeNumbers::examples_ = nullptr;
std::vector<ScriptRun>* ReadmeNumbers::runs_ = nullptr;

TEST_F(ReadmeNumbers, BothExamplesRunToTheirReport) {
  for (std::size_t i = 0; i < runs_->size(); ++i) {
    const auto& [name, folder] = (*examples_)[i];
    EXPECT_EQ((*runs_)[i].exit_code, 0) << name << ":\n" << Tail((*runs_)[i].log);
    EXPECT_TRUE(fs::exists(folder / "report.html")) << name;
    EXPECT_TRUE(fs::exists(folder / "diagnosis.json")) << name;
  }
}

TEST_F(ReadmeNumbers, EveryQuotedNumberIsTheExamplesOwn) {
  std::size_t checked = 0;
  std::set<std::string> files_with_markers;
  for (const fs::path& file : DocumentationFiles()) {
    for (const Comparison& c : CheckMarkers(ReadText(file), file.string(), *examples_)) {
      std::cout << c.line << "\n";
      if (!c.ok) ADD_FAILURE() << c.line;
      ++checked;
      files_with_markers.insert(file.string());
    }
  }
  std::cout << checked << " quoted numbers and names checked\n";
  // The two guides quote both examples: markers lost in an edit fail here.
  EXPECT_TRUE(files_with_markers.count("README.md"));
  EXPECT_TRUE(files_with_markers.count("examples/concealed_friction/README.md"));
}

// The page's data block (one per page), parsed.
nlohmann::json ReportDataBlock(const std::string& page) {
  const std::string open = "<script type=\"application/json\" id=\"beamid-report-data\">";
  const std::size_t begin = page.find(open);
  if (begin == std::string::npos) return nullptr;
  const std::size_t start = begin + open.size();
  return nlohmann::json::parse(page.substr(start, page.find("</script>", start) - start));
}

// The text of figure `id` (its plot and caption); "" when the page has none.
std::string FigureText(const std::string& page, const std::string& id) {
  const std::size_t begin = page.find("<figure class=\"plot\" id=\"" + id + "\">");
  return begin == std::string::npos ? "" : page.substr(begin, page.find("</figure>", begin) - begin);
}

// What each example's report states is what its analysis found: the data
// block against result.json and diagnosis.json, and after the concealed
// friction's diagnosis, the selected model drawn beside the base.
TEST_F(ReadmeNumbers, EachExamplesReportStatesItsAnalysis) {
  for (const auto& [name, folder] : *examples_) {
    SCOPED_TRACE(name);
    const std::string page = ReadText(folder / "report.html");
    const nlohmann::json block = ReportDataBlock(page);
    ASSERT_TRUE(block.is_object());
    const nlohmann::json result = nlohmann::json::parse(ReadText(folder / "result.json"));
    const nlohmann::json diagnosis = nlohmann::json::parse(ReadText(folder / "diagnosis.json"));
    EXPECT_EQ(block["fit"]["chi_square"], result["fit"]["chi_square"]);
    EXPECT_EQ(block["fit"]["degrees_of_freedom"], result["fit"]["degrees_of_freedom"]);
    EXPECT_EQ(block["model"]["kind"], result["model"]["kind"]);
    const nlohmann::json& stated = block["diagnosis"];
    EXPECT_EQ(stated["verdict"], diagnosis["verdict"]);
    EXPECT_EQ(stated["selected"], diagnosis["selected"]);
    EXPECT_EQ(stated["rest_within_noise"], diagnosis["rest_within_noise"]);
    const bool named = diagnosis["verdict"] == "cause named";
    EXPECT_EQ(named, name == "friction");
    const std::string after = FigureText(page, "residual-map-selected");
    const std::string backbone = FigureText(page, "backbone-plot");
    if (!named) {
      EXPECT_EQ(after, "");
      EXPECT_EQ(backbone.find("backbone of the selected model"), std::string::npos);
      continue;
    }
    EXPECT_EQ(stated["blame"], diagnosis["blame"]);
    const std::string selected = diagnosis["selected"][0].get<std::string>();
    EXPECT_NE(after.find(fmt::format("χ² {:.6g} on the map; {:.6g} in its fit",
                                     diagnosis["final"]["fit"]["chi_square"].get<double>(),
                                     diagnosis["final"]["fit"]["chi_square"].get<double>())),
              std::string::npos)
        << after.substr(after.find("<figcaption>"));
    EXPECT_NE(FigureText(page, "residual-map").find(fmt::format("χ² {:.6g} on the map",
                                                                diagnosis["base"]["chi_square"].get<double>())),
              std::string::npos);
    EXPECT_NE(backbone.find("backbone of the selected model"), std::string::npos);
    EXPECT_NE(backbone.find("the model the diagnosis selected (" + selected + ")"), std::string::npos);
    EXPECT_NE(FigureText(page, "held-out-selected-acc3"), "");
  }
}

TEST_F(ReadmeNumbers, AMarkerThatNamesNothingFails) {
  const std::string text =
      "a <!-- check demo no_such_file.json /a rel 0.1 -->1.0\n"
      "b <!-- check demo result.json /no/such/pointer rel 0.1 -->1.0\n"
      "c <!-- check elsewhere result.json /parameters rel 0.1 -->1.0\n"
      "d <!-- check demo result.json /parameters/k1/value -->150\n"
      "e <!-- check demo result.json /parameters/k1/value rel 0.1 -->about 150\n"
      "f <!-- check demo result.json /parameters/k1/value rel 1e-9 -->1.5·10²\n"
      "g <!-- check demo result.json /parameters/k1/value rel 0.01 -->1.5·10²\n";
  const std::vector<Comparison> comparisons = CheckMarkers(text, "text", *examples_);
  ASSERT_EQ(comparisons.size(), 7u);
  for (std::size_t i = 0; i + 1 < comparisons.size(); ++i) {
    std::cout << comparisons[i].line << "\n";
    EXPECT_FALSE(comparisons[i].ok) << comparisons[i].line;
  }
  EXPECT_NE(comparisons[0].line.find("no_such_file.json"), std::string::npos);
  EXPECT_NE(comparisons[1].line.find("/no/such/pointer"), std::string::npos);
  // The last one is right: k1 ≈ 150 within 1 %.
  EXPECT_TRUE(comparisons.back().ok) << comparisons.back().line;
}

TEST(ReadmeNumberFormat, TheDocumentationsNumbersAreRead) {
  EXPECT_EQ(ParseQuotedNumber("150.43 N")->first, 150.43);
  EXPECT_DOUBLE_EQ(ParseQuotedNumber("\u22121.7\u00b710\u2074 x")->first, -1.7e4);
  EXPECT_DOUBLE_EQ(ParseQuotedNumber("1.90\u00b710\u207b\u2074")->first, 1.90e-4);
  EXPECT_DOUBLE_EQ(ParseQuotedNumber("3.9e-5")->first, 3.9e-5);
  EXPECT_EQ(ParseQuotedNumber("12 %")->second, 2u);
  EXPECT_FALSE(ParseQuotedNumber("about"));
  EXPECT_FALSE(ParseQuotedNumber("."));
  EXPECT_EQ(ParseQuotedNumber("261.\n")->second, 3u);
}

TEST(ReadmeLinks, EveryRelativeLinkResolves) {
  for (const fs::path& file : DocumentationFiles())
    for (const std::string& broken : BrokenLinks(file)) ADD_FAILURE() << broken;
}

// The README's command for first-harmonic tables runs on the tables it names.
TEST(ReadmeLinks, TheShippedPhasorTablesGiveAMeasuredBackbone) {
  const fs::path output = testing::UniqueTempPath("beamid_readme_tables");
  fs::create_directories(output);
  solver::ExternalProgram program;
  program.program = BEAMID_EXECUTABLE;
  program.arguments = {"-q",
                       "backbone",
                       "--measured",
                       "examples/phasor_tables/low.csv",
                       "examples/phasor_tables/mid.csv",
                       "examples/phasor_tables/high.csv",
                       "-o",
                       (output / "measured").string()};
  program.stderr_file = output / "stderr.log";
  const int status = solver::RunExternalProgram(program);
  EXPECT_EQ(status, 0) << ReadText(output / "stderr.log");
  EXPECT_TRUE(fs::exists(output / "measured.json"));
  fs::remove_all(output);
}

}  // namespace
}  // namespace beamid
