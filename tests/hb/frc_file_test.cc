// The files of `beamid frc` (hb/frc_file.h): every field the writer writes
// reads back to the same struct, bit for bit (NaN included), and the text read
// and written again is the same text; the CSV's header and rows are the
// struct's values; a file of the earlier inline writer (no "format", keys
// sorted) reads; a damaged file is refused naming the file and the field.
#include "hb/frc_file.h"

#include <bit>
#include <cmath>
#include <complex>
#include <cstdint>
#include <filesystem>
#include <limits>
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
FrcFile Filled() {
  FrcFile f;
  f.beamid_version = "9.8.7";
  f.model = "bench beam";
  f.harmonics = 2;
  f.phasor_convention = "a convention";
  f.first_natural_frequency_hz = 54.123456789;
  f.sensors = {{"acc1", 0.123}, {"acc3", 0.456}};
  for (int c = 0; c < 2; ++c) {
    FrcCurve curve;
    curve.force_N = 0.5 + c;
    curve.turning_points = 2 + c;
    curve.complete = c == 1;
    for (int j = 0; j < 2; ++j) {
      FrcPoint p;
      p.frequency_hz = 53.0 + 0.1234567891 * j + c;
      p.stable = j == 1;
      p.theta_rad = {{1e-6, -2e-7}, {3e-3 + j, -4e-3}, {c == 1 && j == 1 ? kNaN : 5e-5, 6e-5}};
      for (std::size_t s = 0; s < f.sensors.size(); ++s)
        p.sensors.push_back({{{1e-7, 0.0}, {2e-4 + s, -3e-4}, {4e-6, 5e-6 * j}},
                             {{-0.0, 0.0}, {-20.5 - s, 30.25}, {-0.4, 0.5 + c}}});
      curve.points.push_back(p);
    }
    f.curves.push_back(curve);
  }
  return f;
}

void ExpectSame(const FrcFile& a, const FrcFile& b) {
  EXPECT_EQ(a.beamid_version, b.beamid_version);
  EXPECT_EQ(a.model, b.model);
  EXPECT_EQ(a.harmonics, b.harmonics);
  EXPECT_EQ(a.phasor_convention, b.phasor_convention);
  EXPECT_TRUE(Same(a.first_natural_frequency_hz, b.first_natural_frequency_hz));
  ASSERT_EQ(a.sensors.size(), b.sensors.size());
  for (std::size_t i = 0; i < a.sensors.size(); ++i) {
    EXPECT_EQ(a.sensors[i].channel, b.sensors[i].channel);
    EXPECT_TRUE(Same(a.sensors[i].position_m, b.sensors[i].position_m));
  }
  ASSERT_EQ(a.curves.size(), b.curves.size());
  for (std::size_t c = 0; c < a.curves.size(); ++c) {
    SCOPED_TRACE("curve " + std::to_string(c));
    EXPECT_TRUE(Same(a.curves[c].force_N, b.curves[c].force_N));
    EXPECT_EQ(a.curves[c].turning_points, b.curves[c].turning_points);
    EXPECT_EQ(a.curves[c].complete, b.curves[c].complete);
    ASSERT_EQ(a.curves[c].points.size(), b.curves[c].points.size());
    for (std::size_t j = 0; j < a.curves[c].points.size(); ++j) {
      SCOPED_TRACE("point " + std::to_string(j));
      const FrcPoint& x = a.curves[c].points[j];
      const FrcPoint& y = b.curves[c].points[j];
      EXPECT_TRUE(Same(x.frequency_hz, y.frequency_hz));
      EXPECT_EQ(x.stable, y.stable);
      EXPECT_TRUE(Same(x.theta_rad, y.theta_rad));
      ASSERT_EQ(x.sensors.size(), y.sensors.size());
      for (std::size_t s = 0; s < x.sensors.size(); ++s) {
        EXPECT_TRUE(Same(x.sensors[s].displacement_m, y.sensors[s].displacement_m));
        EXPECT_TRUE(Same(x.sensors[s].acceleration_m_s2, y.sensors[s].acceleration_m_s2));
      }
    }
  }
}

using beamid::testing::Cells;
using beamid::testing::G9;
using beamid::testing::Lines;

TEST(FrcFile, EveryFieldSurvivesTheTextAndBackAndTheTextIsStable) {
  const FrcFile original = Filled();
  const std::string text = FrcFileToJson(original);
  const FrcFile read = FrcFileFromJson(text, "frc.json");
  ExpectSame(original, read);
  EXPECT_EQ(FrcFileToJson(read), text);
  EXPECT_THAT(text, HasSubstr("\"format\": \"beamid-frc/1\""));
  EXPECT_THAT(text, HasSubstr("\"command\": \"frc\""));
  EXPECT_THAT(text, HasSubstr("\"beamid_version\": \"9.8.7\""));
  EXPECT_THAT(text, HasSubstr("\"turning_points\": 3"));
  EXPECT_THAT(text, HasSubstr("null"));  // the NaN
}

TEST(FrcFile, ANewFileCarriesThisVersionAndTheConvention) {
  const FrcFile f;
  EXPECT_EQ(f.beamid_version, std::string(kVersion));
  EXPECT_EQ(f.phasor_convention, std::string(kFrcPhasorConvention));
}

TEST(FrcFile, WrittenFileReadsBack) {
  const beamid::testing::TempFile file("frc.json");
  WriteFrcFile(file.path, Filled());
  ExpectSame(Filled(), ReadFrcFile(file.path));
  std::filesystem::remove(file.path);
  const std::string message = InputErrorOf([&] { ReadFrcFile(file.path); });
  EXPECT_THAT(message, HasSubstr(file.path.string()));
  EXPECT_THAT(message, HasSubstr("frequency response file"));
}

TEST(FrcFile, TheCsvHeaderAndRowsAreTheStructsValues) {
  const FrcFile f = Filled();
  const std::vector<std::string> lines = Lines(FrcFileToCsv(f));
  ASSERT_EQ(lines.size(), 1u + 4u);  // header, 2 curves × 2 points
  EXPECT_EQ(lines[0],
            "force_N,frequency_Hz,stable,theta_h1_amp_rad,theta_h1_phase_rad,theta_h2_amp_rad,theta_h2_phase_rad,"
            "acc1_h1_disp_amp_m,acc1_h1_disp_phase_rad,acc1_h1_acc_amp_m_s2,acc1_h1_acc_phase_rad,"
            "acc1_h2_disp_amp_m,acc1_h2_disp_phase_rad,acc1_h2_acc_amp_m_s2,acc1_h2_acc_phase_rad,"
            "acc3_h1_disp_amp_m,acc3_h1_disp_phase_rad,acc3_h1_acc_amp_m_s2,acc3_h1_acc_phase_rad,"
            "acc3_h2_disp_amp_m,acc3_h2_disp_phase_rad,acc3_h2_acc_amp_m_s2,acc3_h2_acc_phase_rad");
  // The second curve's first point.
  const FrcPoint& p = f.curves[1].points[0];
  const std::vector<std::string> row = Cells(lines[3]);
  ASSERT_EQ(row.size(), Cells(lines[0]).size());
  EXPECT_EQ(row[0], "1.5");
  EXPECT_EQ(row[1], G9(p.frequency_hz));
  EXPECT_EQ(row[2], "0");
  EXPECT_EQ(row[3], G9(std::abs(p.theta_rad[1])));
  EXPECT_EQ(row[4], G9(std::arg(p.theta_rad[1])));
  EXPECT_EQ(row[5], G9(std::abs(p.theta_rad[2])));
  EXPECT_EQ(row[6], G9(std::arg(p.theta_rad[2])));
  const FrcSensorPhasors& acc3 = p.sensors[1];
  EXPECT_EQ(row[15], G9(std::abs(acc3.displacement_m[1])));
  EXPECT_EQ(row[16], G9(std::arg(acc3.displacement_m[1])));
  EXPECT_EQ(row[17], G9(std::abs(acc3.acceleration_m_s2[1])));
  EXPECT_EQ(row[18], G9(std::arg(acc3.acceleration_m_s2[1])));
  EXPECT_EQ(row[22], G9(std::arg(acc3.acceleration_m_s2[2])));
  EXPECT_EQ(Cells(lines[2])[2], "1");  // the first curve's second point is stable
}

TEST(FrcFile, APointThatDoesNotMatchTheSensorsIsNotWritten) {
  FrcFile f = Filled();
  f.curves[0].points[1].sensors.pop_back();
  EXPECT_THROW(FrcFileToJson(f), std::invalid_argument);
  EXPECT_THROW(FrcFileToCsv(f), std::invalid_argument);
}

// As the inline writer of `beamid frc` wrote it before the struct (keys sorted).
constexpr const char* kEarlierFile = R"({
 "beamid_version": "0.9.0",
 "command": "frc",
 "curves": [
  {"complete": true, "force_N": 1.0,
   "points": [
    {"frequency_Hz": 53.5,
     "sensors": {"acc1": {"acceleration_m_s2": [[0.0, 0.0], [-1.0, 2.0]], "displacement_m": [[0.0, 0.0], [1e-4, -2e-4]],
                          "position_m": 0.2}},
     "stable": true, "theta_rad": [[0.0, 0.0], [1e-3, 2e-3]]}
   ],
   "turning_points": 0}
 ],
 "first_natural_frequency_Hz": 54.0,
 "harmonics": 1,
 "model": "m",
 "phasor_convention": "x(t) = X0 + sum_k Re(X_k exp(i k w t)), peak amplitudes, SI"
})";

TEST(FrcFile, AFileOfTheEarlierWriterReads) {
  const FrcFile f = FrcFileFromJson(kEarlierFile, "old.json");
  EXPECT_EQ(f.beamid_version, "0.9.0");
  EXPECT_EQ(f.harmonics, 1);
  ASSERT_EQ(f.sensors.size(), 1u);
  EXPECT_EQ(f.sensors[0].channel, "acc1");
  EXPECT_EQ(f.sensors[0].position_m, 0.2);
  ASSERT_EQ(f.curves.size(), 1u);
  ASSERT_EQ(f.curves[0].points.size(), 1u);
  EXPECT_EQ(f.curves[0].points[0].sensors[0].acceleration_m_s2[1], std::complex<double>(-1.0, 2.0));
  EXPECT_EQ(f.curves[0].points[0].theta_rad[1], std::complex<double>(1e-3, 2e-3));
}

// The text of Filled() with `from` replaced by `to` (which must occur).
std::string Damaged(const std::string& from, const std::string& to) {
  std::string text = FrcFileToJson(Filled());
  const std::size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

TEST(FrcFile, ADamagedFileIsRefusedNamingTheFileAndTheField) {
  std::string message =
      InputErrorOf([] { FrcFileFromJson(Damaged("\"beamid-frc/1\"", "\"beamid-backbone/1\""), "x.json"); });
  EXPECT_THAT(message, HasSubstr("x.json"));
  EXPECT_THAT(message, HasSubstr("\"format\""));
  message = InputErrorOf(
      [] { FrcFileFromJson(Damaged("\"command\": \"frc\"", "\"command\": \"predict\""), "x.json"); });
  EXPECT_THAT(message, HasSubstr("\"command\""));
  message = InputErrorOf([] { FrcFileFromJson(Damaged("\"harmonics\": 2,", ""), "x.json"); });
  EXPECT_THAT(message, HasSubstr("x.json: field \"harmonics\" is missing"));
  message = InputErrorOf([] { FrcFileFromJson(Damaged("\"turning_points\": 2,", ""), "x.json"); });
  EXPECT_THAT(message, HasSubstr("field \"curves[0].turning_points\" is missing"));
  ExpectRefused([] { FrcFileFromJson(Damaged("\"stable\": false", "\"stable\": 0"), "x.json"); },
                "curves[0].points[0].stable");
  ExpectRefused([] { FrcFileFromJson(Damaged("\"model\": \"bench beam\"", "\"model\": 3"), "x.json"); }, "model");
  message = InputErrorOf([] { FrcFileFromJson(Damaged("\"complete\"", "\"completed\""), "x.json"); });
  EXPECT_THAT(message, HasSubstr("curves[0].completed"));
  message = InputErrorOf([] { FrcFileFromJson(Damaged("\"harmonics\": 2", "\"harmonics\": 3"), "x.json"); });
  EXPECT_THAT(message, HasSubstr("curves[0].points[0].theta_rad"));
  message = InputErrorOf([] { FrcFileFromJson("[1, 2]", "x.json"); });
  EXPECT_THAT(message, HasSubstr("x.json: not a frequency response file"));
}

TEST(FrcFile, PointsNamingOtherSensorsAreRefused) {
  // The second point of the first curve names acc2 where the first has acc3.
  std::string text = FrcFileToJson(Filled());
  const std::size_t first = text.find("\"acc3\"");
  const std::size_t second = text.find("\"acc3\"", first + 1);
  ASSERT_NE(second, std::string::npos);
  text.replace(second, 6, "\"acc2\"");
  const std::string message = InputErrorOf([&] { FrcFileFromJson(text, "x.json"); });
  EXPECT_THAT(message, HasSubstr("curves[0].points[1].sensors"));
}

TEST(FrcFile, TheDeclarationHoldsForEveryField) {
  beamid::testing::ExpectDeclarationHolds({
      .fields = FrcFileFields(),
      .sample = FrcFileToJson(Filled()),
      .read = [](const std::string& text) { FrcFileFromJson(text, "x.json"); },
      .rewrite = [](const std::string& text) { return FrcFileToJson(FrcFileFromJson(text, "x.json")); },
  });
}

}  // namespace
}  // namespace beamid::hb
