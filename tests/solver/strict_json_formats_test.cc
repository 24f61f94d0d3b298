// Every JSON format beamid reads goes through the one strict parser
// (hb/strict_json.h): in each, a key written twice deep inside the file is
// refused before any field is read, naming the file, the key's path and the
// fix (a lenient parser would keep one of the two values, and the reader
// would complain about some other field, or none). The worker records of the
// fits, read from another process, refuse it too.
#include <fstream>
#include <functional>
#include <sstream>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "hb/backbone_file.h"
#include "hb/errors.h"
#include "hb/frc_file.h"
#include "hb/model_file.h"
#include "hb/scenario.h"
#include "signal/campaign.h"
#include "signal/phasor_set_io.h"
#include "solver/backbone/measured_backbone_io.h"
#include "solver/diagnosis/diagnosis_io.h"
#include "solver/estimation/prediction_io.h"
#include "solver/estimation/result_io.h"
#include "solver/estimation/start_record_io.h"
#include "tests/support/expect_refused.h"

namespace beamid {
namespace {

using beamid::testing::InputErrorOf;
using ::testing::HasSubstr;

struct Format {
  std::string name;
  std::string format;  // its "format" field
  std::function<void(const std::string& text, const std::string& source)> read;
};

// A file of the format whose "beam.length_m" is written twice, three levels deep.
std::string WithDuplicate(const std::string& format) {
  return R"({"format": ")" + format + R"(", "x": [{"beam": {"length_m": 0.6, "width_m": 0.04, "length_m": 6.0}}]})";
}

TEST(StrictJsonFormats, EveryFormatRefusesAKeyWrittenTwice) {
  const std::vector<Format> formats = {
      {"model", std::string(hb::kModelFileFormat), [](auto& t, auto& s) { hb::ParseModelFile(t, s); }},
      {"scenario", std::string(hb::kScenarioFormat), [](auto& t, auto& s) { hb::ParseScenario(t, s); }},
      {"campaign", std::string(signal::kCampaignFormat),
       [](auto& t, auto& s) { signal::ParseCampaign(t, "folder", s); }},
      {"phasors", std::string(signal::kPhasorFormat), [](auto& t, auto& s) { signal::PhasorSetFromJson(t, s); }},
      {"result", std::string(solver::kResultFormat), [](auto& t, auto& s) { solver::ResultFileFromJson(t, s); }},
      {"diagnosis", std::string(solver::kDiagnosisFormat),
       [](auto& t, auto& s) { solver::DiagnosisFileFromJson(t, s); }},
      {"prediction", std::string(solver::kPredictionFormat),
       [](auto& t, auto& s) { solver::PredictionFileFromJson(t, s); }},
      {"frc", std::string(hb::kFrcFormat), [](auto& t, auto& s) { hb::FrcFileFromJson(t, s); }},
      {"backbone", std::string(hb::kBackboneFormat), [](auto& t, auto& s) { hb::BackboneFileFromJson(t, s); }},
      {"measured backbone", std::string(solver::kMeasuredBackboneFormat),
       [](auto& t, auto& s) { solver::MeasuredBackboneFileFromJson(t, s); }},
  };
  for (const Format& f : formats) {
    SCOPED_TRACE(f.name);
    const std::string source = "dir/" + f.name + ".json";
    const std::string message = InputErrorOf([&] { f.read(WithDuplicate(f.format), source); });
    EXPECT_THAT(message, HasSubstr(source + ": the key \"length_m\" is written twice in one object (at "
                                            "\"x[0].beam.length_m\")"));
    EXPECT_THAT(message, HasSubstr("Fix: keep one of the two entries"));
  }
}

TEST(StrictJsonFormats, TheWorkerRecordsRefuseAKeyWrittenTwice) {
  try {
    solver::StartRecordFromText(R"({"objective": 1, "objective": 2})");
    ADD_FAILURE() << "accepted";
  } catch (const std::runtime_error& e) {
    EXPECT_THAT(e.what(), HasSubstr("\"objective\" is written twice"));
  }
  try {
    solver::CandidateRefitFromText(R"({"chi_square": 1, "chi_square": 2})");
    ADD_FAILURE() << "accepted";
  } catch (const std::runtime_error& e) {
    EXPECT_THAT(e.what(), HasSubstr("\"chi_square\" is written twice"));
  }
}

// A file of a real 3-step run (the fuzz seeds; the tests run in the source
// folder) with the first `from` replaced by `to`.
std::string SeedWith(const std::string& path, const std::string& from, const std::string& to) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  std::string s = text.str();
  const std::size_t at = s.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return at == std::string::npos ? s : s.replace(at, from.size(), to);
}

TEST(StrictJsonFormats, ValuesOutsideTheirRangeAreRefusedNamingTheField) {
  const std::string phasors = "tests/fuzz/seeds/phasor_json_fuzzer/phasors.json";
  EXPECT_NO_THROW(signal::PhasorSetFromJson(SeedWith(phasors, "", ""), "p.json"));
  EXPECT_THAT(InputErrorOf([&] {
                signal::PhasorSetFromJson(SeedWith(phasors, "\"std_re\": 6.97", "\"std_re\": -6.97"), "p.json");
              }),
              HasSubstr("p.json: channel 'force': field \"steps[0].channels[0].harmonics[0].std_re\" = -6.97"));
  EXPECT_THAT(InputErrorOf([&] {
                signal::PhasorSetFromJson(SeedWith(phasors, "\"frequency_Hz\": 53.6", "\"frequency_Hz\": -53.6"),
                                          "p.json");
              }),
              HasSubstr("field \"steps[0].frequency_Hz\" = -53.6"));
  const std::string diagnosis = "tests/fuzz/seeds/diagnosis_json_fuzzer/diagnosis.json";
  EXPECT_NO_THROW(solver::DiagnosisFileFromJson(SeedWith(diagnosis, "", ""), "d.json"));
  EXPECT_THAT(InputErrorOf([&] {
                solver::DiagnosisFileFromJson(SeedWith(diagnosis, "\"p_value\": 0.0077", "\"p_value\": 1.0077"),
                                              "d.json");
              }),
              HasSubstr("p_value\" = 1.0077"));
  const std::string result = "tests/fuzz/seeds/result_json_fuzzer/result.json";
  EXPECT_NO_THROW(solver::ResultFileFromJson(SeedWith(result, "", ""), "r.json"));
}

}  // namespace
}  // namespace beamid
