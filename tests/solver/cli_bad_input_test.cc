// Every bad input a hostile or careless user has tried, in one table, run
// through the real program: each must end with exit code 2 (bad input) and a
// message holding the key words that name the file, channel or option at
// fault and the fix, never a crash (exit 1 "internal error"), never exit 3
// ("did not converge") for something the user can fix, and never a silent
// answer. The campaign is a 3-step simulation made once for the table; each
// row spoils its own copy.
#include <sys/stat.h>
#include <sys/wait.h>

#include <cmath>
#include <complex>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "solver/backbone/measured_backbone_io.h"
#include "tests/signal/uff58_writer.h"
#include "tests/support/file_bytes.h"
#include "tests/support/paper_scenario.h"
#include "tests/support/temp_path.h"

namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

using beamid::testing::ProgramRun;
using beamid::testing::ReadFile;
using beamid::testing::WriteFile;

// Replaces the first occurrence of `text` in the file.
void Replace(const fs::path& path, const std::string& text, const std::string& replacement) {
  std::string content = ReadFile(path);
  const std::size_t at = content.find(text);
  ASSERT_NE(at, std::string::npos) << text << " not found in " << path;
  WriteFile(path, content.replace(at, text.size(), replacement));
}

// Removes the step of `file` from campaign.json's list ("{...}" and the
// comma before it).
void RemoveStep(const fs::path& campaign_json, const std::string& file) {
  std::string content = ReadFile(campaign_json);
  const std::size_t at = content.find(file);
  ASSERT_NE(at, std::string::npos) << file << " not in " << campaign_json;
  const std::size_t open = content.rfind('{', at), close = content.find('}', at);
  const std::size_t comma = content.rfind(',', open);
  WriteFile(campaign_json, content.erase(comma, close + 1 - comma));
}

// A measured backbone file of one level, flagged with a jump, whose peak
// lies at `peak_hz`.
void WriteMeasuredBackbone(const fs::path& path, double peak_hz) {
  beamid::solver::MeasuredBackboneFile file;
  file.inputs = {"low.csv"};
  file.channel = "acc1";
  file.response_quantity = "acceleration";
  beamid::solver::LevelResonance level;
  level.label = "low";
  level.peak_frequency_hz = {.value = peak_hz, .std = 0.01, .valid = true};
  level.flags = {{.kind = beamid::solver::LevelFlagKind::kJump, .quantity = "sweep", .message = "a jump"}};
  file.levels = {level};
  beamid::solver::WriteMeasuredBackboneFile(path, file);
}

// Replaces the value of `column` (0-based) on CSV line `line` (1-based, the
// header is line 1).
void ReplaceSample(const fs::path& path, int line, int column, const std::string& value) {
  std::istringstream in(ReadFile(path));
  std::string out, row;
  for (int n = 1; std::getline(in, row); ++n) {
    if (n == line) {
      std::vector<std::string> fields;
      std::stringstream cells(row);
      for (std::string cell; std::getline(cells, cell, ',');) fields.push_back(cell);
      fields.at(static_cast<std::size_t>(column)) = value;
      row.clear();
      for (std::size_t i = 0; i < fields.size(); ++i) row += (i ? "," : "") + fields[i];
    }
    out += row + "\n";
  }
  WriteFile(path, out);
}

// Changes the value of `column` (0-based) on CSV line `line` in its last
// significant digits: another recording of the same rig, files and levels,
// that extracts like the first.
void NudgeSample(const fs::path& path, int line, int column) {
  std::istringstream in(ReadFile(path));
  std::string row;
  for (int n = 1; std::getline(in, row) && n < line; ++n) {
  }
  std::vector<std::string> fields;
  std::stringstream cells(row);
  for (std::string cell; std::getline(cells, cell, ',');) fields.push_back(cell);
  std::string value = fields.at(static_cast<std::size_t>(column));
  const std::size_t exponent = value.find_first_of("eE");
  value.insert(exponent == std::string::npos ? value.size() : exponent, value.find('.') == std::string::npos ? ".1" : "1");
  ReplaceSample(path, line, column, value);
}

// Removes the line of the file that holds `key` (a JSON member written on
// its own line, as beamid writes them).
void RemoveLineWith(const fs::path& path, const std::string& key) {
  std::string content = ReadFile(path);
  const std::size_t at = content.find(key);
  ASSERT_NE(at, std::string::npos) << key << " not in " << path;
  const std::size_t start = content.rfind('\n', at) + 1, end = content.find('\n', at);
  WriteFile(path, content.erase(start, end + 1 - start));
}

class BadInput : public ::testing::Test {
 protected:
  static ProgramRun Beamid(const std::string& arguments) {
    const fs::path log = root_ / "run.log";
    const std::string command = std::string(BEAMID_EXECUTABLE) + " " + arguments + " > " + log.string() + " 2>&1";
    const int status = std::system(command.c_str());
    return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, ReadFile(log)};
  }

  static void SetUpTestSuite() {
    root_ = beamid::testing::UniqueTempPath("beamid_bad_input");
    fs::remove_all(root_);
    fs::create_directories(root_);
    scenario_ = beamid::testing::PaperScenarioJson("bad input table", R"([
      {"label": "low", "force_amplitude_N": 0.5, "frequencies_Hz": {"start": 53.6, "stop": 54.6, "step": 0.5}}])", 3);
    WriteFile(root_ / "scenario.json", scenario_);
    setup_ = Beamid("-q simulate " + (root_ / "scenario.json").string() + " -o " + (root_ / "clean").string());
    if (setup_.exit_code == 0)
      setup_ = Beamid("-q identify " + (root_ / "clean").string() + " --fit acc1,acc2 -o " +
                      (root_ / "result.json").string());
  }
  static void TearDownTestSuite() { fs::remove_all(root_); }

  void SetUp() override { ASSERT_EQ(setup_.exit_code, 0) << setup_.output; }

  static inline fs::path root_;
  static inline std::string scenario_;
  static inline ProgramRun setup_;
};

struct Row {
  std::string what;
  // Spoils the copy of the campaign (folder m) or writes other inputs into
  // the row's folder.
  std::function<void(const fs::path& m, const fs::path& row)> spoil;
  // {m}: the spoiled campaign, {c}: the clean one, {r}: its result.json,
  // {d}: the row's folder.
  std::string arguments;
  std::vector<std::string> key_words;
};

std::string Expand(std::string text, const fs::path& m, const fs::path& c, const fs::path& r, const fs::path& d) {
  for (const auto& [key, value] : {std::pair{"{m}", m}, {"{c}", c}, {"{r}", r}, {"{d}", d}})
    for (std::size_t at; (at = text.find(key)) != std::string::npos;) text.replace(at, 3, value.string());
  return text;
}

TEST_F(BadInput, EveryBadInputEndsWithExitTwoAndAMessageThatNamesItAndTheFix) {
  const auto step = [](const fs::path& m, int i) { return m / "low" / ("step_00" + std::to_string(i) + ".csv"); };
  const auto scenario_with = [](const std::string& text, const std::string& replacement) {
    return [=](const fs::path&, const fs::path& d) {
      std::string scenario = scenario_;
      const std::size_t at = scenario.find(text);
      ASSERT_NE(at, std::string::npos) << text;
      WriteFile(d / "s.json", scenario.replace(at, text.size(), replacement));
    };
  };
  const auto model_with = [](const std::string& text, const std::string& replacement) {
    return [=](const fs::path&, const fs::path& d) {
      std::string model = ReadFile("examples/paper_setup/model.json");
      const std::size_t at = model.find(text);
      ASSERT_NE(at, std::string::npos) << text;
      WriteFile(d / "model.json", model.replace(at, text.size(), replacement));
    };
  };
  std::string many_sensors;
  for (int i = 0; i < 65; ++i)
    many_sensors += "{\"channel\": \"s" + std::to_string(i) + "\", \"position_m\": 0.1},";
  // The fuzzer's seed diagnosis.json (a real run's) with the first `text` replaced.
  const auto diagnosis_with = [](const std::string& text, const std::string& replacement) {
    return [=](const fs::path&, const fs::path& d) {
      std::string diagnosis = ReadFile("tests/fuzz/seeds/diagnosis_json_fuzzer/diagnosis.json");
      const std::size_t at = diagnosis.find(text);
      ASSERT_NE(at, std::string::npos) << text;
      WriteFile(d / "d.json", diagnosis.replace(at, text.size(), replacement));
    };
  };
  // The identified result with k1's value (the first parameter's) replaced by edit(value).
  const auto result_with = [](std::function<std::string(std::string)> edit) {
    return [=](const fs::path&, const fs::path& d) {
      std::string result = ReadFile(root_ / "result.json");
      const std::size_t k1 = result.find("\"k1\": {", result.find("\"parameters\": {"));
      ASSERT_NE(k1, std::string::npos);
      const std::size_t value = result.find("\"value\": ", k1) + 9, end = result.find(',', value);
      WriteFile(d / "result.json", result.replace(value, end - value, edit(result.substr(value, end - value))));
    };
  };
  const std::vector<Row> rows = {
      // campaign.json
      {"a number beyond double range",
       [](auto m, auto) { Replace(m / "campaign.json", "\"length_m\": 0.6", "\"length_m\": 1e400"); },
       "extract {m} -o {d}/p.json", {"campaign.json", "1e400", "Fix:"}},
      {"a beam of 1e300 m", [](auto m, auto) { Replace(m / "campaign.json", "\"length_m\": 0.6", "\"length_m\": 1e300"); },
       "identify {m} -o {d}/r.json", {"campaign.json", "\"beam.length_m\" = 1e+300 lies outside 0.001 .. 100", "Fix:"}},
      {"a step file outside the campaign folder",
       [](auto m, auto) { Replace(m / "campaign.json", "low/step_000.csv", "../../../../etc/passwd"); },
       "extract {m} -o {d}/p.json", {"campaign.json", "lies outside the campaign folder", "Fix:"}},
      {"a key written twice",
       [](auto m, auto) { Replace(m / "campaign.json", "\"name\": \"bad input table\"", "\"name\": \"a\", \"name\": \"b\""); },
       "extract {m} -o {d}/p.json", {"campaign.json", "\"name\" is written twice", "Fix:"}},
      {"one recording named by two steps",
       [](auto m, auto) { Replace(m / "campaign.json", "low/step_001.csv", "low/step_000.csv"); },
       "extract {m} -o {d}/p.json", {"campaign.json", "named by another step", "Fix:"}},
      {"an unknown unit", [](auto m, auto) { Replace(m / "campaign.json", "\"m/s^2\"", "\"furlong\""); },
       "extract {m} -o {d}/p.json", {"campaign.json", "acc1", "furlong", "Fix:"}},
      {"no campaign.json (a half-written campaign)", [](auto m, auto) { fs::remove(m / "campaign.json"); },
       "extract {m} -o {d}/p.json", {"campaign.json", "no such file", "Fix:"}},
      {"a folder in place of campaign.json",
       [](auto m, auto) { fs::remove(m / "campaign.json"); fs::create_directory(m / "campaign.json"); },
       "identify {m} -o {d}/r.json", {"campaign.json", "it is a folder", "Fix:"}},
      // recordings
      {"a sample of 1e308", [&](auto m, auto) { ReplaceSample(step(m, 1), 5, 1, "1e308"); },
       "extract {m} -o {d}/p.json", {"step_001.csv", "force", "beyond any measurement", "Fix:"}},
      {"one wild force sample", [&](auto m, auto) { ReplaceSample(step(m, 1), 5, 1, "900"); },
       "identify {m} -o {d}/r.json", {"step_001.csv", "force", "spike", "Fix:"}},
      {"NaN in a recording", [&](auto m, auto) { ReplaceSample(step(m, 2), 9, 3, "nan"); },
       "extract {m} -o {d}/p.json", {"step_002.csv", "acc2", "NaN", "line 9", "Fix:"}},
      // A column no channel uses is ignored; the channel it replaced is missing.
      {"a channel renamed in the header", [&](auto m, auto) { Replace(step(m, 1), "acc2", "acc9"); },
       "extract {m} -o {d}/p.json", {"step_001.csv", "channel 'acc2'", "missing from the header", "acc9", "Fix:"}},
      {"time going backwards", [&](auto m, auto) { ReplaceSample(step(m, 1), 5, 0, "0.0009"); },
       "extract {m} -o {d}/p.json", {"step_001.csv", "time does not increase", "Fix:"}},
      {"a record of one period", [&](auto m, auto) {
         std::istringstream in(ReadFile(step(m, 1)));
         std::string out, line;
         for (int n = 0; n < 100 && std::getline(in, line); ++n) out += line + "\n";
         WriteFile(step(m, 1), out);
       },
       "extract {m} -o {d}/p.json", {"step_001.csv", "too short", "Fix:"}},
      {"a sample rate that the time column contradicts",
       [](auto m, auto) { Replace(m / "campaign.json", "\"sample_rate_Hz\": 5120.0", "\"sample_rate_Hz\": 5000"); },
       "extract {m} -o {d}/p.json", {"sample_rate_Hz", "5000", "Fix:"}},
      {"a missing recording", [&](auto m, auto) { fs::remove(step(m, 2)); },
       "extract {m} -o {d}/p.json", {"step_002.csv", "is missing", "Fix:"}},
      {"a voltage excitation given to identify",
       [](auto m, auto) {
         Replace(m / "campaign.json", "\"quantity\": \"force\"", "\"quantity\": \"voltage\"");
         Replace(m / "campaign.json", "\"unit\": \"N\"", "\"unit\": \"V\"");
       },
       "identify {m} -o {d}/r.json", {"campaign.json", "the excitation is a voltage", "force transducer", "Fix:"}},
      {"a base-acceleration excitation given to diagnose",
       [](auto m, auto) {
         Replace(m / "campaign.json", "\"quantity\": \"force\"", "\"quantity\": \"base_acceleration\"");
         Replace(m / "campaign.json", "\"unit\": \"N\"", "\"unit\": \"m/s^2\"");
       },
       "diagnose {m} -o {d}/d.json", {"campaign.json", "the excitation is a base_acceleration", "model-free", "Fix:"}},
      {"two bad recordings without --skip-bad-steps", [&](auto m, auto) {
         ReplaceSample(step(m, 0), 9, 3, "nan");
         ReplaceSample(step(m, 2), 9, 3, "nan");
       },
       "identify {m} -o {d}/r.json", {"2 of 3 steps cannot be analysed", "step_000.csv", "step_002.csv", "--skip-bad-steps"}},
      {"a fitted channel that campaign.json ignores",
       [](auto m, auto) { Replace(m / "campaign.json", "\"sample_rate_Hz\"", "\"ignore_channels\": [\"acc2\"], \"sample_rate_Hz\""); },
       "identify {m} --fit acc1,acc2 -o {d}/r.json", {"acc2", "ignore_channels", "Fix:"}},
      // results, phasors, models and scenarios
      {"a folder given as result.json", [](auto, auto d) { fs::create_directories(d / "result.json"); },
       "predict {d}/result.json --x 0.3 -o {d}/pred.json", {"result.json", "folder"}},
      {"a folder given to report", [](auto, auto d) { fs::create_directories(d / "result.json"); },
       "report {d}/result.json -o {d}/report.html", {"result.json", "folder"}},
      {"phasors of a 2-step subset", [](auto m, auto d) {
         fs::remove(m / "low" / "step_002.csv");
         RemoveStep(m / "campaign.json", "low/step_002.csv");
         ASSERT_EQ(Beamid("-q extract " + m.string() + " -o " + (d / "p.json").string()).exit_code, 0);
       },
       "identify {c} --phasors {d}/p.json -o {d}/r.json", {"p.json", "not the campaign's", "Fix:"}},
      {"a result of another campaign given to diagnose",
       [](auto m, auto) { Replace(m / "campaign.json", "\"name\": \"bad input table\"", "\"name\": \"another\""); },
       "diagnose {m} --result {r} -o {d}/d.json", {"--result", "not of campaign 'another'", "Fix:"}},
      {"a result of another campaign given to predict",
       [](auto m, auto) { Replace(m / "campaign.json", "\"name\": \"bad input table\"", "\"name\": \"another\""); },
       "predict {r} --campaign {m} --x 0.57 -o {d}/pred.json", {"result.json", "not of campaign 'another'", "Fix:"}},
      {"a channel fitted twice", nullptr, "identify {c} --fit acc1,acc1 -o {d}/r.json", {"acc1", "listed twice"}},
      {"a model with 100000 harmonics", nullptr, "frc examples/paper_setup/model.json -H 100000 -o {d}/f",
       {"--harmonics"}},
      {"a record of 1e6 s", scenario_with("\"record_s\": 0.4", "\"record_s\": 1e6"), "simulate {d}/s.json -o {d}/sim",
       {"s.json", "record_s"}},
      {"a time step of 1e-12 s", scenario_with("\"timing\": {", "\"timing\": {\"max_time_step_s\": 1e-12, "),
       "simulate {d}/s.json -o {d}/sim", {"s.json", "max_time_step_s"}},
      {"a scenario beam of 1e300 m", scenario_with("\"length_m\": 0.6", "\"length_m\": 1e300"),
       "simulate {d}/s.json -o {d}/sim", {"s.json", "length_m", "1 mm to 100 m", "Fix:"}},
      // recording readers: what is no table, numbers, units, what stands in a step's place
      {"a recording of NUL bytes", [&](auto m, auto) { WriteFile(step(m, 1), std::string(1 << 20, '\0')); },
       "extract {m} -o {d}/p.json", {"step_001.csv", "byte 1 (line 1) is a NUL", "not a text table", "Fix:"}},
      {"a recording of one 2 MB line", [&](auto m, auto) { WriteFile(step(m, 1), std::string(2 << 20, 'x')); },
       "extract {m} -o {d}/p.json", {"step_001.csv", "2097152 bytes long", "Fix:"}},
      {"a sample of 1e400", [&](auto m, auto) { ReplaceSample(step(m, 1), 5, 1, "1e400"); },
       "extract {m} -o {d}/p.json", {"step_001.csv", "force", "'1e400' is out of range", "Fix:"}},
      {"a header unit that contradicts campaign.json",
       [&](auto m, auto) { Replace(step(m, 0), "acc1", "acc1 [g]"); },
       "identify {m} --fit acc1,acc2 -o {d}/r.json",
       {"step_000.csv", "acc1", "the header gives the unit 'g' but campaign.json declares 'm/s^2'", "Fix:"}},
      {"a folder as a step's recording",
       [&](auto m, auto) { fs::remove(step(m, 1)); fs::create_directory(step(m, 1)); },
       "extract {m} -o {d}/p.json", {"step_001.csv", "is a folder, not a file", "Fix:"}},
      {"a UFF record 9 unit that contradicts campaign.json",
       [&](auto m, auto) {
         std::istringstream in(ReadFile(step(m, 1)));
         std::string line;
         std::getline(in, line);  // time_s,force,acc1,acc2,acc3
         std::vector<std::vector<double>> columns(5);
         while (std::getline(in, line)) {
           std::stringstream cells(line);
           std::string cell;
           for (std::size_t c = 0; std::getline(cells, cell, ','); ++c) columns.at(c).push_back(std::stod(cell));
         }
         std::string uff;
         const char* const names[] = {"force", "acc1", "acc2", "acc3"};
         for (std::size_t c = 0; c < 4; ++c) {
           beamid::testing::UffChannel channel;
           channel.id_line1 = names[c];
           channel.unit = c == 1 ? "g" : "";  // campaign.json: m/s^2
           channel.x_min = columns[0].front();
           channel.dx = (columns[0].back() - columns[0].front()) / static_cast<double>(columns[0].size() - 1);
           channel.values = columns[c + 1];
           uff += beamid::testing::UffDataset58(channel, beamid::testing::UffEncoding::kBinaryLittleDouble);
         }
         WriteFile(m / "low" / "step_001.uff", uff);
         fs::remove(step(m, 1));
         Replace(m / "campaign.json", "low/step_001.csv", "low/step_001.uff");
       },
       "extract {m} -o {d}/p.json",
       {"step_001.uff", "acc1", "record 9 gives the unit 'g' but campaign.json declares 'm/s^2'", "Fix:"}},
      {"a FIFO as a step's recording",
       [&](auto m, auto) { fs::remove(step(m, 1)); ASSERT_EQ(::mkfifo(step(m, 1).c_str(), 0600), 0); },
       "extract {m} -o {d}/p.json", {"step_001.csv", "is a FIFO, not a file", "Fix:"}},
      // strict JSON (hb/strict_json.h): a key written twice is refused in every format, the values the
      // readers take are checked for range, and the lists of points on the beam are bounded
      {"a model with length_m written twice", model_with("\"length_m\": 0.600", "\"length_m\": 0.6, \"length_m\": 6.0"),
       "frc {d}/model.json -o {d}/f", {"model.json", "\"length_m\" is written twice", "beam.length_m", "Fix:"}},
      {"a model with 65 sensors", model_with("{ \"channel\": \"acc1\", \"position_m\": 0.100 },", many_sensors),
       "frc {d}/model.json -o {d}/f", {"model.json", "\"sensors\" holds", "not at most 64", "Fix:"}},
      {"a scenario with k1 written twice", scenario_with("\"k1_Nm_rad\": 150", "\"k1_Nm_rad\": 150, \"k1_Nm_rad\": 15"),
       "simulate {d}/s.json -o {d}/sim", {"s.json", "\"k1_Nm_rad\" is written twice", "Fix:"}},
      {"a result with k1.value written twice", result_with([](std::string value) { return "1000, \"value\": " + value; }),
       "predict {d}/result.json --x 0.3 -o {d}/pred.json",
       {"result.json", "\"value\" is written twice", "parameters.k1.value", "Fix:"}},
      {"a result with k1 = -5", result_with([](const std::string&) { return std::string("-5"); }),
       "predict {d}/result.json --x 0.3 -o {d}/pred.json",
       {"result.json", "parameters.k1.value", "-5 is negative", "Fix:"}},
      {"phasors with a key written twice",
       [](auto m, auto d) {
         ASSERT_EQ(Beamid("-q extract " + m.string() + " -o " + (d / "p.json").string()).exit_code, 0);
         Replace(d / "p.json", "\"num_harmonics\": ", "\"num_harmonics\": 3, \"num_harmonics\": ");
       },
       "identify {m} --phasors {d}/p.json -o {d}/r.json", {"p.json", "\"num_harmonics\" is written twice", "Fix:"}},
      // consistency: files derived from another campaign of the same name, files
      // and levels (told by the campaign's content hash), fitted channels held
      // out, fits of no channel
      {"phasors of another campaign with the same files and levels",
       [](auto m, auto d) {
         NudgeSample(m / "low" / "step_001.csv", 500, 3);
         ASSERT_EQ(Beamid("-q extract " + m.string() + " -o " + (d / "p.json").string()).exit_code, 0);
       },
       "identify {c} --phasors {d}/p.json -o {d}/r.json",
       {"--phasors", "p.json", "campaign.json", "content SHA-256", "Fix:", "extract"}},
      {"phasors written before the campaign's content hash",
       [](auto, auto d) {
         ASSERT_EQ(Beamid("-q extract " + (root_ / "clean").string() + " -o " + (d / "p.json").string()).exit_code, 0);
         RemoveLineWith(d / "p.json", "\"campaign_sha256\"");
       },
       "diagnose {c} --phasors {d}/p.json -o {d}/d.json", {"p.json", "written by an older beamid", "Fix:", "extract"}},
      {"a result given to report with another campaign of the same layout",
       [](auto m, auto) { NudgeSample(m / "low" / "step_002.csv", 400, 2); },
       "report {r} --campaign {m} -o {d}/report.html",
       {"result.json", "campaign.json", "content SHA-256", "Fix:", "--campaign"}},
      {"a result given to predict with another campaign of the same name",
       [](auto m, auto) { NudgeSample(m / "low" / "step_000.csv", 300, 2); },
       "predict {r} --campaign {m} --x 0.57 -o {d}/pred.json", {"result.json", "campaign.json", "content SHA-256", "Fix:"}},
      {"a result given to diagnose with another campaign of the same name",
       [](auto m, auto) { NudgeSample(m / "low" / "step_000.csv", 300, 2); },
       "diagnose {m} --result {r} -o {d}/d.json", {"--result", "result.json", "content SHA-256", "Fix:"}},
      {"a result written before the campaign's content hash",
       [](auto, auto d) {
         fs::copy_file(root_ / "result.json", d / "old.json");
         RemoveLineWith(d / "old.json", "\"campaign_sha256\"");
       },
       "predict {d}/old.json --campaign {c} --x 0.57 -o {d}/pred.json", {"old.json", "written by an older beamid", "Fix:"}},
      {"a fitted channel held out by identify", nullptr, "identify {c} --fit acc1,acc2 --validate acc1 -o {d}/r.json",
       {"--validate acc1", "also fitted", "Fix:"}},
      {"a fitted channel held out by diagnose", nullptr, "diagnose {c} --fit acc1,acc2 --validate acc2 -o {d}/d.json",
       {"--validate acc2", "also fitted", "Fix:"}},
      {"every sensor ignored",
       [](auto m, auto) {
         Replace(m / "campaign.json", "\"sample_rate_Hz\"", "\"ignore_channels\": [\"acc1\", \"acc2\", \"acc3\"], \"sample_rate_Hz\"");
       },
       "identify {m} -o {d}/r.json", {"campaign.json", "no sensor is left to fit", "ignore_channels", "Fix:"}},
      {"every sensor not ignored held out",
       [](auto m, auto) {
         Replace(m / "campaign.json", "\"sample_rate_Hz\"", "\"ignore_channels\": [\"acc1\", \"acc2\"], \"sample_rate_Hz\"");
       },
       "diagnose {m} --validate acc3 -o {d}/d.json", {"campaign.json", "no sensor is left to fit", "--validate", "Fix:"}},
      // Control characters in names and labels: a line break in a label
      // would end a command of the plots' gnuplot scripts.
      {"a line break in a level label",
       [](auto m, auto) { Replace(m / "campaign.json", "\"level\": \"low\"", "\"level\": \"low\\nset output 'x'\""); },
       "diagnose {m} -o {d}/d.json --curves {d}/c",
       {"campaign.json", "\"steps[0].level\" holds the control character 0x0A", "Fix:", "one line of printable text"}},
      {"a tab in a channel name",
       [](auto m, auto) { Replace(m / "campaign.json", "\"channel\": \"acc1\"", "\"channel\": \"acc\\t1\""); },
       "report {r} --campaign {m} -o {d}/report.html", {"campaign.json", "\"sensors[0].channel\" holds the control character 0x09", "Fix:"}},
      {"a DEL in a step's file name",
       [](auto m, auto) { Replace(m / "campaign.json", "low/step_001.csv", "low/step\\u007f_001.csv"); },
       "extract {m} -o {d}/p.json", {"campaign.json", "\"steps[1].file\" holds the control character 0x7F", "Fix:"}},
      {"an escape character in a unit",
       [](auto m, auto) { Replace(m / "campaign.json", "\"unit\": \"m/s^2\"", "\"unit\": \"m/s^2\\u001b[0m\""); },
       "extract {m} -o {d}/p.json", {"campaign.json", "channel 'acc1'", "\"sensors[0].unit\" holds the control character 0x1B", "Fix:"}},
      {"a line break in a scenario's sensor name",
       scenario_with("{\"channel\": \"acc1\"", "{\"channel\": \"acc1\\n\""), "simulate {d}/s.json -o {d}/sim",
       {"s.json", "sensors[0].channel", "control character", "Fix:"}},
      // outputs and option ranges (solver/workflow/output_paths.h, checks before any work)
      {"an empty -o", nullptr, "extract {c} -o ''", {"-o", "empty"}},
      {"an empty --phasors", nullptr, "identify {c} --phasors '' -o {d}/r.json", {"--phasors", "empty"}},
      {"an empty --csv", nullptr, "extract {c} --csv '' -o {d}/p.json", {"--csv", "empty"}},
      {"an empty frc prefix", nullptr, "frc examples/paper_setup/model.json -o ''", {"-o", "empty"}},
      {"frc from 0 Hz", nullptr, "frc examples/paper_setup/model.json --from-hz 0 -o {d}/f", {"--from-hz", "finite"}},
      {"frc from -1 Hz", nullptr, "frc examples/paper_setup/model.json --from-hz -1 -o {d}/f", {"--from-hz", "finite"}},
      {"frc from NaN Hz", nullptr, "frc examples/paper_setup/model.json --from-hz nan -o {d}/f", {"--from-hz", "finite"}},
      {"frc to 1 GHz", nullptr, "frc examples/paper_setup/model.json --to-hz 1e9 -o {d}/f", {"--to-hz", "finite"}},
      {"frc far above the first mode", nullptr, "frc examples/paper_setup/model.json --from-hz 5000 --to-hz 6000 -o {d}/f",
       {"--from-hz", "first natural frequency"}},
      {"an infinite force", nullptr, "frc examples/paper_setup/model.json --force-N inf -o {d}/f", {"--force-N", "finite"}},
      {"a negative force", nullptr, "frc examples/paper_setup/model.json --force-N 1,-2 -o {d}/f", {"--force-N"}},
      {"frc without points", nullptr, "frc examples/paper_setup/model.json --max-points 0 -o {d}/f", {"--max-points"}},
      {"a backbone of 1e8 points", nullptr, "backbone examples/paper_setup/model.json --points 100000000 -o {d}/b",
       {"--points"}},
      {"a backbone from above its end", nullptr,
       "backbone examples/paper_setup/model.json --min-theta-rad 0.1 --max-theta-rad 0.01 -o {d}/b",
       {"--min-theta-rad", "--max-theta-rad"}},
      {"an infinite backbone amplitude", nullptr, "backbone examples/paper_setup/model.json --max-theta-rad inf -o {d}/b",
       {"--max-theta-rad"}},
      {"a backbone without harmonics", nullptr, "backbone examples/paper_setup/model.json -H 0 -o {d}/b", {"--harmonics"}},
      {"a NaN loss factor", nullptr, "identify {c} --beam-loss-factor nan -o {d}/r.json", {"--beam-loss-factor"}},
      {"a NaN significance", nullptr, "diagnose {c} --significance nan -o {d}/d.json", {"--significance"}},
      {"a NaN position", nullptr, "predict {r} --x nan -o {d}/p.json", {"--x"}},
      {"a position off the beam", nullptr, "predict {r} --x 5 -o {d}/p.json", {"--x", "outside the beam"}},
      {"a negative thread count", nullptr, "extract {c} --threads -1 -o {d}/p.json", {"--threads"}},
      {"extract without harmonics", nullptr, "extract {c} -H 0 -o {d}/p.json", {"--harmonics"}},
      // measured backbone files given to report (solver/backbone/measured_backbone_io.h): one level
      // written by the real writer, then spoiled.
      {"a measured backbone with a negative peak frequency",
       [](auto, auto d) { WriteMeasuredBackbone(d / "bb.json", -54.0); },
       "report {d}/bb.json -o {d}/report.html", {"bb.json", "levels[0].peak.frequency_Hz.value", "-54", "Fix:"}},
      {"a measured backbone flag of an unknown kind",
       [](auto, auto d) {
         WriteMeasuredBackbone(d / "bb.json", 54.0);
         Replace(d / "bb.json", "\"kind\": \"jump\"", "\"kind\": \"jumped\"");
       },
       "report {d}/bb.json -o {d}/report.html", {"bb.json", "levels[0].flags[0].kind", "\"jumped\"", "Fix:"}},
      // model file and scenario, declared once (hb/json_schema.h): a misspelt key, another variant's field, a
      // count that is no integer, a frequency range of 1e300 steps, a base-excited scenario as a model
      {"a model with k3 misspelt", model_with("\"k3_Nm_rad3\"", "\"k3_Nm_rad\""), "frc {d}/model.json -o {d}/f",
       {"model.json", "\"support.polynomial.k3_Nm_rad\" is not a field here", "Fix:"}},
      {"an amplifier on a force drive", scenario_with("\"position_m\": 0.57}", "\"position_m\": 0.57, \"amplifier_sag\": 0.2}"),
       "simulate {d}/s.json -o {d}/sim", {"s.json", "\"excitation.amplifier_sag\" belongs to a voltage drive", "Fix:"}},
      {"a seed of 1.5", scenario_with("\"noise\": {\"seed\": ", "\"noise\": {\"seed\": 1.5, \"x\": "),
       "simulate {d}/s.json -o {d}/sim", {"s.json", "\"noise.seed\" must be an integer", "Fix:"}},
      {"a range of 1e300 steps",
       scenario_with("\"levels\": [", "\"levels\": [{\"label\": \"huge\", \"force_amplitude_N\": 1, "
                     "\"frequencies_Hz\": {\"start\": 1, \"stop\": 1e300, \"step\": 1e-300}}, "),
       "simulate {d}/s.json -o {d}/sim", {"s.json", "levels[0].frequencies_Hz.step", "at most 100000 steps", "Fix:"}},
      {"a base-excited scenario as a model",
       scenario_with("\"excitation\": {\"channel\": \"force\", \"position_m\": 0.57}",
                     "\"excitation\": {\"channel\": \"base\", \"quantity\": \"base_acceleration\"}"),
       "frc {d}/s.json -o {d}/f", {"s.json", "\"excitation.quantity\"", "drives the beam with a force", "Fix:"}},
      // result.json, read from its declaration (solver/estimation/result_io.cc)
      {"a result with a misspelled key",
       [](const fs::path&, const fs::path& d) {
         std::string result = ReadFile(root_ / "result.json");
         const std::size_t at = result.find("\"minimum_decisive\"");
         ASSERT_NE(at, std::string::npos);
         WriteFile(d / "result.json", result.replace(at, 18, "\"minimum_decsive\""));
       },
       "predict {d}/result.json --x 0.3 -o {d}/pred.json",
       {"result.json", "fit.minimum_decsive", "is not a field here", "Fix:"}},
      {"a result with a correlation of 2",
       [](const fs::path&, const fs::path& d) {
         std::string result = ReadFile(root_ / "result.json");
         const std::size_t key = result.find("\"correlation\"");
         ASSERT_NE(key, std::string::npos);
         const std::size_t row = result.find('[', result.find('[', key) + 1);
         const std::size_t value = result.find_first_not_of(" \n", row + 1), end = result.find(',', value);
         WriteFile(d / "result.json", result.replace(value, end - value, "2.0"));
       },
       "predict {d}/result.json --x 0.3 -o {d}/pred.json", {"result.json", "correlation[0][0]", "= 2 lies outside", "Fix:"}},
      // campaign.json and phasors, each read by its one declaration
      // (hb/campaign_file.h, signal/phasor_set_io.cc): the field's path, the
      // channel the field belongs to, and the fix
      {"a misspelt key of a sensor in campaign.json",
       [](auto m, auto) { Replace(m / "campaign.json", "\"position_m\": 0.3,", "\"postion_m\": 0.3,"); },
       "extract {m} -o {d}/p.json",
       {"campaign.json", "channel 'acc2'", "field \"sensors[1].postion_m\" is not a field here", "Fix:", "position_m"}},
      {"a negative sensor mass in campaign.json",
       [](auto m, auto) {
         Replace(m / "campaign.json", "\"position_m\": 0.3,", "\"position_m\": 0.3, \"mass_kg\": -0.004,");
       },
       "identify {m} -o {d}/r.json",
       {"campaign.json", "channel 'acc2'", "field \"sensors[1].mass_kg\" = -0.004 lies outside ≥ 0", "Fix:"}},
      {"phasors with a misspelt key",
       [](auto m, auto d) {
         ASSERT_EQ(Beamid("-q extract " + m.string() + " -o " + (d / "p.json").string()).exit_code, 0);
         Replace(d / "p.json", "\"num_harmonics\": ", "\"num_harmonic\": 3, \"num_harmonics\": ");
       },
       "identify {m} --phasors {d}/p.json -o {d}/r.json", {"p.json", "field \"num_harmonic\" is not a field here", "Fix:"}},
      {"phasors that call a response the excitation",
       [](auto m, auto d) {
         ASSERT_EQ(Beamid("-q extract " + m.string() + " -o " + (d / "p.json").string()).exit_code, 0);
         Replace(d / "p.json", "\"role\": \"response\"", "\"role\": \"excitation\"");
       },
       "identify {m} --phasors {d}/p.json -o {d}/r.json",
       {"p.json", "channel 'acc1'", "field \"steps[0].channels[1].role\" breaks the rule", "Fix:"}},
      // diagnosis.json (solver/diagnosis/diagnosis_io.h) as report reads it: a real file (the fuzzer's seed), spoilt.
      {"a diagnosis whose verdict is none the diagnosis gives",
       diagnosis_with("\"verdict\": \"no significant discrepancy\"", "\"verdict\": \"the weather\""),
       "report {d}/d.json -o {d}/report.html", {"d.json", "\"verdict\"", "\"the weather\"", "not one of", "Fix:"}},
      {"a diagnosis with a p-value above 1", diagnosis_with("\"p_value\": 1.0", "\"p_value\": 1.5"),
       "report {d}/d.json -o {d}/report.html", {"d.json", "p_value\"", "lies outside 0 .. 1", "Fix:"}},
      {"a diagnosis with a misspelt key", diagnosis_with("\"rest_within_noise\"", "\"rest_within_nois\""),
       "report {d}/d.json -o {d}/report.html", {"d.json", "\"rest_within_nois\"", "is not a field here", "Fix:"}},
  };
  const fs::path clean = root_ / "clean", result = root_ / "result.json";
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const Row& row = rows[i];
    SCOPED_TRACE(row.what);
    const fs::path d = root_ / ("row" + std::to_string(i)), m = d / "campaign";
    fs::create_directories(d);
    fs::copy(clean, m, fs::copy_options::recursive);
    if (row.spoil) row.spoil(m, d);
    const std::string arguments = Expand(row.arguments, m, clean, result, d);
    const ProgramRun run = Beamid(arguments);
    EXPECT_EQ(run.exit_code, 2) << arguments << "\n" << run.output;
    for (const auto& word : row.key_words) EXPECT_THAT(run.output, HasSubstr(word)) << arguments;
    EXPECT_THAT(run.output, ::testing::Not(HasSubstr("internal error"))) << arguments;
  }
}

// What a channel no analysis uses holds is no reason to stop: a NaN in a
// channel campaign.json ignores is a note, in a channel that --channel and
// --fit leave out a warning; a Latin-1 header of an extra column is a note
// (its bytes escaped in the phasors file); a recording with CR line ends is
// read as any other.
TEST_F(BadInput, WhatNoAnalysisUsesIsANoteOrAWarningNeverAStop) {
  const fs::path d = root_ / "unused", m = d / "campaign";
  fs::create_directories(d);
  fs::copy(root_ / "clean", m, fs::copy_options::recursive);
  ReplaceSample(m / "low" / "step_001.csv", 9, 4, "nan");  // acc3
  Replace(m / "campaign.json", "\"sample_rate_Hz\"", "\"ignore_channels\": [\"acc3\"], \"sample_rate_Hz\"");
  {
    std::string csv = ReadFile(m / "low" / "step_002.csv");
    std::string with_column;
    std::istringstream in(csv);
    for (std::string row; std::getline(in, row);)
      with_column += row + (with_column.empty() ? ",temp [\xB0" "C]" : ",21.5") + "\r";
    WriteFile(m / "low" / "step_002.csv", with_column);
  }
  const ProgramRun extracted = Beamid("extract " + m.string() + " -o " + (d / "p.json").string());
  ASSERT_EQ(extracted.exit_code, 0) << extracted.output;
  const std::string phasors = ReadFile(d / "p.json");
  EXPECT_THAT(phasors, HasSubstr("channel 'acc3' (ignored in campaign.json): NaN or infinite value at line 9"));
  EXPECT_THAT(phasors, HasSubstr("column 6's header 'temp [\\\\xB0C]' is not UTF-8 text"));
  const ProgramRun identified =
      Beamid("identify " + m.string() + " --fit acc1,acc2 -o " + (d / "r.json").string());
  EXPECT_EQ(identified.exit_code, 0) << identified.output;

  // Not ignored, but not analysed by this run.
  Replace(m / "campaign.json", "\"ignore_channels\": [\"acc3\"], ", "");
  const ProgramRun channel = Beamid("extract " + m.string() + " --channel acc1 -o " + (d / "p2.json").string());
  ASSERT_EQ(channel.exit_code, 0) << channel.output;
  EXPECT_THAT(ReadFile(d / "p2.json"), HasSubstr("channel 'acc3' (not analysed): NaN or infinite value at line 9"));
  const ProgramRun all = Beamid("extract " + m.string() + " -o " + (d / "p3.json").string());
  EXPECT_EQ(all.exit_code, 2) << all.output;
  EXPECT_THAT(all.output, HasSubstr("channel 'acc3': NaN or infinite value at line 9"));
}

// The exit code does not depend on whether the error can be printed: with
// stderr on a full device the run still ends with exit 2, not an abort.
TEST_F(BadInput, AnErrorOnAFullStderrStillEndsWithItsExitCode) {
  for (const std::string global : {"-q", "--progress json"}) {
    const std::string command = std::string(BEAMID_EXECUTABLE) + " " + global + " extract " +
                                (root_ / "no_such_campaign").string() + " -o " + (root_ / "x.json").string() +
                                " 2>/dev/full";
    const int status = std::system(command.c_str());
    ASSERT_TRUE(WIFEXITED(status)) << command;
    EXPECT_EQ(WEXITSTATUS(status), 2) << command;
  }
  // Progress and summaries on a full stderr are dropped; the run goes on.
  for (const std::string global : {"", "--progress json"}) {
    const std::string command = std::string(BEAMID_EXECUTABLE) + " " + global +
                                " frc examples/paper_setup/model.json --force-N 1 --from-hz 53 --to-hz 56 -o " +
                                (root_ / "full_stderr").string() + " > /dev/null 2>/dev/full";
    const int status = std::system(command.c_str());
    ASSERT_TRUE(WIFEXITED(status)) << command;
    EXPECT_EQ(WEXITSTATUS(status), 0) << command;
    EXPECT_TRUE(fs::exists(root_ / "full_stderr.json")) << command;
    fs::remove(root_ / "full_stderr.json");
  }
}

// The way out that the error above names: with --skip-bad-steps the other
// steps are fitted, the skipped one is named on stderr and in the phasors
// file, and identify reading that file needs the flag too.
TEST_F(BadInput, SkipBadStepsFitsTheOtherStepsAndNamesTheSkippedOne) {
  const fs::path d = root_ / "skip", m = d / "campaign";
  fs::create_directories(d);
  fs::copy(root_ / "clean", m, fs::copy_options::recursive);
  ReplaceSample(m / "low" / "step_001.csv", 9, 3, "nan");
  const ProgramRun identified = Beamid("identify " + m.string() + " --fit acc1,acc2 --skip-bad-steps -o " +
                                       (d / "r.json").string());
  ASSERT_EQ(identified.exit_code, 0) << identified.output;
  EXPECT_THAT(identified.output, HasSubstr("warning: skipped low/step_001.csv"));
  EXPECT_THAT(identified.output, HasSubstr("from 2 steps"));
  const ProgramRun extracted =
      Beamid("extract " + m.string() + " --skip-bad-steps -o " + (d / "p.json").string());
  ASSERT_EQ(extracted.exit_code, 0) << extracted.output;
  EXPECT_THAT(extracted.output, HasSubstr("2 steps (1 skipped)"));
  EXPECT_THAT(ReadFile(d / "p.json"), HasSubstr("\"skipped_steps\""));
  const ProgramRun without_flag =
      Beamid("identify " + m.string() + " --phasors " + (d / "p.json").string() + " -o " + (d / "r2.json").string());
  EXPECT_EQ(without_flag.exit_code, 2) << without_flag.output;
  EXPECT_THAT(without_flag.output, HasSubstr("--skip-bad-steps"));
  const ProgramRun with_flag = Beamid("identify " + m.string() + " --skip-bad-steps --phasors " +
                                      (d / "p.json").string() + " -o " + (d / "r2.json").string());
  EXPECT_EQ(with_flag.exit_code, 0) << with_flag.output;
}

// backbone --measured CAMPAIGN reads the recordings as extract does: a bad
// sample of a sensor other than --channel's stops nothing, one of the
// channel's stops the run naming --skip-bad-steps, and with it the step is
// left out and named (here the level is then too short for a backbone: the
// complaint is the level's, no longer the recording's).
TEST_F(BadInput, MeasuredBackboneHonoursChannelAndSkipBadSteps) {
  const fs::path d = root_ / "backbone_skip", m = d / "campaign";
  fs::create_directories(d);
  fs::copy(root_ / "clean", m, fs::copy_options::recursive);
  ReplaceSample(m / "low" / "step_001.csv", 9, 3, "nan");  // acc2
  const ProgramRun other_channel =
      Beamid("backbone --measured " + m.string() + " --channel acc1 -o " + (d / "acc1").string());
  ASSERT_EQ(other_channel.exit_code, 0) << other_channel.output;
  EXPECT_TRUE(fs::exists(d / "acc1.json"));

  const ProgramRun without_flag =
      Beamid("backbone --measured " + m.string() + " --channel acc2 -o " + (d / "acc2").string());
  EXPECT_EQ(without_flag.exit_code, 2) << without_flag.output;
  EXPECT_THAT(without_flag.output, HasSubstr("step_001.csv"));
  EXPECT_THAT(without_flag.output, HasSubstr("--skip-bad-steps"));
  const ProgramRun with_flag =
      Beamid("backbone --measured " + m.string() + " --channel acc2 --skip-bad-steps -o " + (d / "acc2").string());
  EXPECT_THAT(with_flag.output, HasSubstr("warning: skipped low/step_001.csv"));
  EXPECT_THAT(with_flag.output, HasSubstr("2 steps; at least 3 are needed"));
  EXPECT_THAT(with_flag.output, ::testing::Not(HasSubstr("cannot be analysed")));

  const ProgramRun on_tables = Beamid("backbone --measured examples/phasor_tables/low.csv --skip-bad-steps -o " +
                                      (d / "tables").string());
  EXPECT_EQ(on_tables.exit_code, 2) << on_tables.output;
  EXPECT_THAT(on_tables.output, HasSubstr("--skip-bad-steps applies to a campaign folder"));
}

// A laser vibrometer's FRF export (a metadata block without '#', its own
// column names, units on the row under the header) is read as it comes when
// the command line says its layout; without it the refusal names the
// options; on a campaign they are refused (campaign.json says its layout).
TEST_F(BadInput, MeasuredTablesTakeAnExportsLayoutAndColumnsFromTheCommandLine) {
  const fs::path d = root_ / "backbone_export";
  fs::create_directories(d);
  // One linear mode, 80.2 Hz, ζ 0.2 %, as a velocity per newton at 0.5 N; 41 steps of 50 mHz.
  std::ostringstream text;
  text << "Source File Name:\tscan_0001.svd\nSignal:\tFRF Vib / Ref1\nDate:\t03.12.2026 21:00\n\n"
       << "X-Data\tShaker Force\tLaser (M - Filtered)\tPhase Laser\n[Hz]\t[N]\t[m/s]\t[deg]\n";
  text.precision(12);
  for (int i = 0; i <= 40; ++i) {
    const double f = 79.2 + 0.05 * i, r = f / 80.2, omega_n = 2 * M_PI * 80.2;
    const std::complex<double> velocity =
        0.5 * std::complex<double>(0, 2 * M_PI * f) / std::complex<double>(1 - r * r, 2 * 0.002 * r) / (omega_n * omega_n);
    text << f << "\t0.5\t" << std::abs(velocity) << "\t" << std::arg(velocity) * 180 / M_PI << "\n";
  }
  WriteFile(d / "level 0.5 N.txt", text.str());
  const std::string table = "'" + (d / "level 0.5 N.txt").string() + "'";
  const std::string layout = " --lines-before-header 4 --units-row --column frequency=X-Data --column excitation=2 "
                             "--column 'response=Laser (M - Filtered)' --column 'phase=Phase Laser'";
  const ProgramRun read = Beamid("backbone --measured " + table + layout + " -o " + (d / "vib").string());
  ASSERT_EQ(read.exit_code, 0) << read.output;
  const beamid::solver::MeasuredBackboneFile measured = beamid::solver::ReadMeasuredBackboneFile(d / "vib.json");
  ASSERT_EQ(measured.levels.size(), 1u);
  EXPECT_NEAR(measured.levels[0].quadrature_frequency_hz.value, 80.2, 1e-6);
  EXPECT_NEAR(measured.levels[0].damping_ratio.value, 0.002, 1e-6);

  const ProgramRun unread = Beamid("backbone --measured " + table + " -o " + (d / "vib2").string());
  EXPECT_EQ(unread.exit_code, 2) << unread.output;
  EXPECT_THAT(unread.output, HasSubstr("level 0.5 N.txt: column 'frequency': missing"));
  EXPECT_THAT(unread.output, HasSubstr("--column ROLE=COLUMN"));
  EXPECT_FALSE(fs::exists(d / "vib2.json"));

  const ProgramRun bad_role = Beamid("backbone --measured " + table + " --column speed=3 -o " + (d / "vib3").string());
  EXPECT_EQ(bad_role.exit_code, 2) << bad_role.output;
  EXPECT_THAT(bad_role.output, HasSubstr("--column speed=3: not ROLE=COLUMN"));

  const ProgramRun on_campaign = Beamid("backbone --measured " + (root_ / "clean").string() +
                                        " --units-row -o " + (d / "campaign").string());
  EXPECT_EQ(on_campaign.exit_code, 2) << on_campaign.output;
  EXPECT_THAT(on_campaign.output, HasSubstr("apply to first-harmonic CSV tables"));
}

// Not bad input: a recording copied over another step's is analysed, but
// every command that reads the recordings warns, naming both files.
TEST_F(BadInput, ARecordingThatCopiesAnotherStepIsAWarningNamingBoth) {
  const fs::path d = root_ / "duplicate", m = d / "campaign";
  fs::create_directories(d);
  fs::copy(root_ / "clean", m, fs::copy_options::recursive);
  fs::copy_file(m / "low" / "step_002.csv", m / "low" / "step_001.csv", fs::copy_options::overwrite_existing);
  const ProgramRun run = Beamid("extract " + m.string() + " -o " + (d / "p.json").string());
  EXPECT_EQ(run.exit_code, 0) << run.output;
  EXPECT_THAT(run.output, HasSubstr("beamid extract: warning: the recording " + (m / "low" / "step_002.csv").string() +
                                    " of steps[2] holds the same bytes as " + (m / "low" / "step_001.csv").string()));
  // The clean campaign has no such warning.
  const ProgramRun clean = Beamid("extract " + (root_ / "clean").string() + " -o " + (d / "clean.json").string());
  EXPECT_EQ(clean.exit_code, 0) << clean.output;
  EXPECT_THAT(clean.output, ::testing::Not(HasSubstr("the same bytes")));
}

// Not bad input: a campaign the model cannot fit (acc2 stated 30 mm from where
// it was glued) is fitted all the same, its result written with the verdict,
// and the exit code 5 says "fitted, but the model misses the data".
TEST_F(BadInput, AModelThatMissesTheDataIsWrittenWithItsVerdictAndExitFive) {
  const fs::path d = root_ / "misfit", m = d / "campaign";
  fs::create_directories(d);
  fs::copy(root_ / "clean", m, fs::copy_options::recursive);
  Replace(m / "campaign.json", "\"position_m\": 0.3,", "\"position_m\": 0.33,");
  // Three steps at one level cannot tell the beam's η from the support's c
  // (both damp the one mode): on this misfit Ipopt wanders along that valley
  // without meeting its tolerance, and the fit ends where χ² stops changing,
  // with its verdict, rather than with no answer (exit 3).
  const ProgramRun run = Beamid("identify " + m.string() + " --fit acc1,acc2 -o " + (d / "r.json").string());
  EXPECT_EQ(run.exit_code, 5) << run.output;
  EXPECT_THAT(run.output, HasSubstr("verdict: misfits beyond the noise"));
  EXPECT_THAT(run.output, HasSubstr("run 'beamid diagnose'"));
  const std::string result = ReadFile(d / "r.json");
  EXPECT_THAT(result, HasSubstr("\"within_noise\": false"));
  // The clean campaign fits within the noise, exit 0.
  const ProgramRun clean = Beamid("identify " + (root_ / "clean").string() + " --fit acc1,acc2 -o " +
                                  (d / "clean.json").string());
  EXPECT_EQ(clean.exit_code, 0) << clean.output;
  EXPECT_THAT(clean.output, HasSubstr("verdict: fits within the noise"));
  EXPECT_THAT(ReadFile(d / "clean.json"), HasSubstr("\"within_noise\": true"));
}

}  // namespace
