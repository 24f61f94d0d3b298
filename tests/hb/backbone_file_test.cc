// The files of `beamid backbone` on a model (hb/backbone_file.h): every field
// the writer writes reads back to the same struct, bit for bit (NaN
// included), and the text read and written again is the same text; the CSV's
// header and rows are the struct's values (an empty cell where there is no
// multiple-scales frequency); a file of the earlier inline writer (no
// "format", keys sorted) reads; a damaged file, or a measured backbone, is
// refused naming the file and the field.
#include "hb/backbone_file.h"

#include <bit>
#include <cmath>
#include <complex>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "hb/errors.h"
#include "tests/support/csv_text.h"
#include "tests/support/same_value.h"
#include "tests/support/schema_checks.h"
#include "tests/support/expect_refused.h"
#include "tests/support/temp_path.h"

namespace beamid::hb {
namespace {

using beamid::testing::Same;

using beamid::testing::ExpectRefused;
using beamid::testing::InputErrorOf;
using ::testing::HasSubstr;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// Every field differs from its default.
BackboneFile Filled() {
  BackboneFile f;
  f.beamid_version = "9.8.7";
  f.model = "bench beam";
  f.definition = "a definition";
  f.harmonics = 2;
  f.complete = false;
  f.sensors = {{"acc1", 0.123}, {"acc3", 0.456}};
  for (int j = 0; j < 3; ++j) {
    BackboneFilePoint p;
    p.theta_amplitude_rad = 1.23456789e-5 * (j + 1);
    p.frequency_hz = 54.0 + 0.0123456789 * j;
    p.force_N = -0.25 + 0.1 * j;
    p.multiple_scales_frequency_hz = j == 2 ? kNaN : 54.01 + j;  // none at the last point
    p.theta_rad = {{1e-7, j == 1 ? kNaN : -2e-8}, {3e-6, -4e-5 * (j + 1)}, {5e-8, 6e-9}};
    for (std::size_t s = 0; s < f.sensors.size(); ++s)
      p.sensors.push_back({.displacement_m = {{-0.0, 1e-9}, {2e-4 * (s + 1), -3e-4 + j}, {4e-6, 5e-6}}});
    f.points.push_back(p);
  }
  return f;
}

void ExpectSame(const BackboneFile& a, const BackboneFile& b) {
  EXPECT_EQ(a.beamid_version, b.beamid_version);
  EXPECT_EQ(a.model, b.model);
  EXPECT_EQ(a.definition, b.definition);
  EXPECT_EQ(a.harmonics, b.harmonics);
  EXPECT_EQ(a.complete, b.complete);
  ASSERT_EQ(a.sensors.size(), b.sensors.size());
  for (std::size_t i = 0; i < a.sensors.size(); ++i) {
    EXPECT_EQ(a.sensors[i].channel, b.sensors[i].channel);
    EXPECT_TRUE(Same(a.sensors[i].position_m, b.sensors[i].position_m));
  }
  ASSERT_EQ(a.points.size(), b.points.size());
  for (std::size_t j = 0; j < a.points.size(); ++j) {
    SCOPED_TRACE("point " + std::to_string(j));
    const BackboneFilePoint& x = a.points[j];
    const BackboneFilePoint& y = b.points[j];
    EXPECT_TRUE(Same(x.theta_amplitude_rad, y.theta_amplitude_rad));
    EXPECT_TRUE(Same(x.frequency_hz, y.frequency_hz));
    EXPECT_TRUE(Same(x.force_N, y.force_N));
    EXPECT_TRUE(Same(x.multiple_scales_frequency_hz, y.multiple_scales_frequency_hz));
    EXPECT_TRUE(Same(x.theta_rad, y.theta_rad));
    ASSERT_EQ(x.sensors.size(), y.sensors.size());
    for (std::size_t s = 0; s < x.sensors.size(); ++s)
      EXPECT_TRUE(Same(x.sensors[s].displacement_m, y.sensors[s].displacement_m));
  }
}

using beamid::testing::Cells;
using beamid::testing::G9;
using beamid::testing::Lines;

TEST(BackboneFile, EveryFieldSurvivesTheTextAndBackAndTheTextIsStable) {
  const BackboneFile original = Filled();
  const std::string text = BackboneFileToJson(original);
  const BackboneFile read = BackboneFileFromJson(text, "bb.json");
  ExpectSame(original, read);
  EXPECT_EQ(BackboneFileToJson(read), text);
  EXPECT_THAT(text, HasSubstr("\"format\": \"beamid-backbone/1\""));
  EXPECT_THAT(text, HasSubstr("\"command\": \"backbone\""));
  EXPECT_THAT(text, HasSubstr("\"beamid_version\": \"9.8.7\""));
  EXPECT_THAT(text, HasSubstr("\"multiple_scales_frequency_Hz\": null"));
}

TEST(BackboneFile, ANewFileCarriesThisVersionAndTheDefinition) {
  const BackboneFile f;
  EXPECT_EQ(f.beamid_version, std::string(kVersion));
  EXPECT_EQ(f.definition, std::string(kBackboneDefinition));
}

TEST(BackboneFile, WrittenFileReadsBack) {
  const beamid::testing::TempFile file("backbone.json");
  WriteBackboneFile(file.path, Filled());
  ExpectSame(Filled(), ReadBackboneFile(file.path));
  std::filesystem::remove(file.path);
  const std::string message = InputErrorOf([&] { ReadBackboneFile(file.path); });
  EXPECT_THAT(message, HasSubstr(file.path.string()));
  EXPECT_THAT(message, HasSubstr("backbone file"));
}

TEST(BackboneFile, TheCsvHeaderAndRowsAreTheStructsValues) {
  const BackboneFile f = Filled();
  const std::vector<std::string> lines = Lines(BackboneFileToCsv(f));
  ASSERT_EQ(lines.size(), 1u + 3u);
  EXPECT_EQ(lines[0],
            "theta_amp_rad,frequency_Hz,force_N,ms_frequency_Hz,acc1_h1_disp_amp_m,acc1_h1_acc_amp_m_s2,"
            "acc3_h1_disp_amp_m,acc3_h1_acc_amp_m_s2");
  const BackboneFilePoint& p = f.points[1];
  const std::vector<std::string> row = Cells(lines[2]);
  ASSERT_EQ(row.size(), 8u);
  EXPECT_EQ(row[0], G9(p.theta_amplitude_rad));
  EXPECT_EQ(row[1], G9(p.frequency_hz));
  EXPECT_EQ(row[2], G9(p.force_N));
  EXPECT_EQ(row[3], G9(p.multiple_scales_frequency_hz));
  const double omega = 2 * std::numbers::pi * p.frequency_hz;
  const double disp = std::abs(p.sensors[1].displacement_m[1]);
  EXPECT_EQ(row[6], G9(disp));
  EXPECT_EQ(row[7], G9(disp * omega * omega));
  // No multiple-scales frequency: an empty cell.
  EXPECT_EQ(Cells(lines[3])[3], "");
}

TEST(BackboneFile, APointThatDoesNotMatchTheSensorsIsNotWritten) {
  BackboneFile f = Filled();
  f.points[2].sensors.pop_back();
  EXPECT_THROW(BackboneFileToJson(f), std::invalid_argument);
  EXPECT_THROW(BackboneFileToCsv(f), std::invalid_argument);
}

// As the inline writer of `beamid backbone` wrote it before the struct (keys sorted).
constexpr const char* kEarlierFile = R"({
 "beamid_version": "0.9.0",
 "command": "backbone",
 "complete": true,
 "definition": "phase resonance: first harmonic of theta in quadrature with the force",
 "harmonics": 1,
 "model": "m",
 "points": [
  {"force_N": 0.01, "frequency_Hz": 54.1, "multiple_scales_frequency_Hz": null,
   "sensors": {"acc1": {"displacement_m": [[0.0, 0.0], [1e-4, -2e-4]], "position_m": 0.2},
               "acc2": {"displacement_m": [[0.0, 0.0], [3e-4, -4e-4]], "position_m": 0.4}},
   "theta_amplitude_rad": 1e-05, "theta_rad": [[0.0, 0.0], [0.0, -1e-05]]}
 ]
})";

TEST(BackboneFile, AFileOfTheEarlierWriterReads) {
  const BackboneFile f = BackboneFileFromJson(kEarlierFile, "old.json");
  EXPECT_EQ(f.beamid_version, "0.9.0");
  EXPECT_TRUE(f.complete);
  ASSERT_EQ(f.sensors.size(), 2u);
  EXPECT_EQ(f.sensors[1].channel, "acc2");
  EXPECT_EQ(f.sensors[1].position_m, 0.4);
  ASSERT_EQ(f.points.size(), 1u);
  EXPECT_TRUE(std::isnan(f.points[0].multiple_scales_frequency_hz));
  EXPECT_EQ(f.points[0].sensors[1].displacement_m[1], std::complex<double>(3e-4, -4e-4));
  EXPECT_EQ(f.points[0].force_N, 0.01);
}

TEST(BackboneFile, AFileOlderThanTheVersionKeyReadsWithNone) {
  std::string text = kEarlierFile;
  const std::string line = " \"beamid_version\": \"0.9.0\",\n";
  ASSERT_NE(text.find(line), std::string::npos);
  text.erase(text.find(line), line.size());
  EXPECT_EQ(BackboneFileFromJson(text, "old.json").beamid_version, "");
}

std::string Damaged(const std::string& from, const std::string& to) {
  std::string text = BackboneFileToJson(Filled());
  const std::size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

TEST(BackboneFile, ADamagedFileIsRefusedNamingTheFileAndTheField) {
  std::string message = InputErrorOf(
      [] { BackboneFileFromJson(Damaged("\"beamid-backbone/1\"", "\"beamid-measured-backbone/1\""), "x.json"); });
  EXPECT_THAT(message, HasSubstr("x.json"));
  EXPECT_THAT(message, HasSubstr("\"format\""));
  message = InputErrorOf(
      [] { BackboneFileFromJson(Damaged("\"command\": \"backbone\"", "\"command\": \"frc\""), "x.json"); });
  EXPECT_THAT(message, HasSubstr("\"command\""));
  message = InputErrorOf([] { BackboneFileFromJson(Damaged("\"complete\": false,", ""), "x.json"); });
  EXPECT_THAT(message, HasSubstr("x.json: field \"complete\" is missing"));
  ExpectRefused([] { BackboneFileFromJson(Damaged("\"complete\": false", "\"complete\": \"no\""), "x.json"); },
                "complete");
  ExpectRefused([] { BackboneFileFromJson(Damaged("\"force_N\": -0.25", "\"force_N\": \"-0.25\""), "x.json"); },
                "points[0].force_N");
  message = InputErrorOf([] { BackboneFileFromJson(Damaged("\"position_m\": 0.123,", ""), "x.json"); });
  EXPECT_THAT(message, HasSubstr("field \"points[0].sensors.acc1.position_m\" is missing"));
  message = InputErrorOf([] { BackboneFileFromJson(Damaged("\"definition\"", "\"defined\""), "x.json"); });
  EXPECT_THAT(message, HasSubstr("\"defined\" is not a field"));
  message = InputErrorOf([] { BackboneFileFromJson("\"text\"", "x.json"); });
  EXPECT_THAT(message, HasSubstr("x.json: not a backbone file"));
}

TEST(BackboneFile, PointsAtOtherSensorPositionsAreRefused) {
  std::string text = BackboneFileToJson(Filled());
  const std::size_t first = text.find("\"position_m\": 0.456");
  const std::size_t second = text.find("\"position_m\": 0.456", first + 1);
  ASSERT_NE(second, std::string::npos);
  text.replace(second, 19, "\"position_m\": 0.457");
  const std::string message = InputErrorOf([&] { BackboneFileFromJson(text, "x.json"); });
  EXPECT_THAT(message, HasSubstr("points[1].sensors.acc3.position_m"));
}

TEST(BackboneFile, TheDeclarationHoldsForEveryField) {
  beamid::testing::ExpectDeclarationHolds({
      .fields = BackboneFileFields(),
      .sample = BackboneFileToJson(Filled()),
      .read = [](const std::string& text) { BackboneFileFromJson(text, "x.json"); },
      .rewrite = [](const std::string& text) { return BackboneFileToJson(BackboneFileFromJson(text, "x.json")); },
  });
}

}  // namespace
}  // namespace beamid::hb
