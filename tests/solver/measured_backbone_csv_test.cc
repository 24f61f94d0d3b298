// The measured backbone's per-level CSV (solver/backbone/measured_backbone_csv.h):
// every row has the header's number of cells; a number not estimated or not
// finite (an infinite σ, a NaN, an infinite regeneration error) is an empty
// cell, never "inf" or "nan"; finite numbers are printed to the digits the
// header promises; a label with a comma is quoted; the excitation's column is named for what drives the
// levels.
#include "solver/backbone/measured_backbone_csv.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "tests/support/csv_text.h"

namespace beamid::solver {
namespace {

using beamid::testing::Cells;
using beamid::testing::Lines;

using ::testing::HasSubstr;
using ::testing::Not;

std::string CellOf(const std::vector<std::string>& header, const std::vector<std::string>& row,
                   const std::string& column) {
  const auto at = std::find(header.begin(), header.end(), column);
  EXPECT_NE(at, header.end()) << column;
  return at == header.end() ? "" : row[static_cast<std::size_t>(at - header.begin())];
}

MeasuredBackbone TwoLevels() {
  MeasuredBackbone measured;
  measured.excitation_quantity = "force";
  LevelResonance good;
  good.label = "low";
  good.quadrature_frequency_hz = {.value = 50.123456789, .std = 0.0012345, .valid = true};
  good.quadrature_damping_ratio = {.value = 0.01, .std = 1e-4, .valid = true};
  good.regeneration_relative_rms = 0.0123456;
  LevelResonance bad;
  bad.label = "high";
  bad.quadrature_frequency_hz = {.value = 50.2, .std = INFINITY, .valid = true};
  bad.quadrature_damping_ratio = {.value = NAN, .std = NAN, .valid = true};
  bad.local_damping_ratio = {.value = -INFINITY, .std = 1e-3, .valid = true};
  bad.regeneration_relative_rms = INFINITY;
  bad.flags.push_back({.kind = LevelFlagKind::kOffBackbone, .quantity = "regeneration_relative_rms", .message = "m"});
  bad.flags.push_back({.kind = LevelFlagKind::kJump, .quantity = "sweep", .message = "j"});
  bad.flags.push_back({.kind = LevelFlagKind::kJump, .quantity = "sweep", .message = "k"});
  bad.in_global_fit = false;
  measured.levels = {good, bad};
  return measured;
}

TEST(MeasuredBackboneCsv, NumbersNotEstimatedOrNotFiniteAreEmptyCells) {
  const std::string text = MeasuredLevelsCsv(TwoLevels());
  EXPECT_THAT(text, Not(HasSubstr("inf")));
  EXPECT_THAT(text, Not(HasSubstr("nan")));
  const std::vector<std::string> lines = Lines(text);
  ASSERT_EQ(lines.size(), 3u);
  const std::vector<std::string> header = Cells(lines[0]);
  for (std::size_t i = 1; i < lines.size(); ++i) EXPECT_EQ(Cells(lines[i]).size(), header.size()) << lines[i];
  const std::vector<std::string> good = Cells(lines[1]), bad = Cells(lines[2]);
  EXPECT_EQ(CellOf(header, good, "quadrature_frequency_Hz"), "50.1234568");
  EXPECT_EQ(CellOf(header, good, "quadrature_frequency_std_Hz"), "0.00123");
  EXPECT_EQ(CellOf(header, good, "regeneration_relative_rms"), "0.01235");
  EXPECT_EQ(CellOf(header, good, "zeta_half_power"), "");  // not estimated
  EXPECT_EQ(CellOf(header, good, "in_global_fit"), "1");
  EXPECT_EQ(CellOf(header, bad, "quadrature_frequency_Hz"), "50.2");
  EXPECT_EQ(CellOf(header, bad, "quadrature_frequency_std_Hz"), "");
  EXPECT_EQ(CellOf(header, bad, "zeta_quadrature"), "");
  EXPECT_EQ(CellOf(header, bad, "zeta_quadrature_std"), "");
  // A σ of a value that is not finite says nothing either.
  EXPECT_EQ(CellOf(header, bad, "zeta_local"), "");
  EXPECT_EQ(CellOf(header, bad, "zeta_local_std"), "");
  EXPECT_EQ(CellOf(header, bad, "regeneration_relative_rms"), "");
  EXPECT_EQ(CellOf(header, bad, "in_global_fit"), "0");
  EXPECT_EQ(CellOf(header, bad, "flags"), "off_backbone;jump");
}

TEST(MeasuredBackboneCsv, TheExcitationColumnIsNamedForWhatDrivesTheLevels) {
  MeasuredBackbone measured = TwoLevels();
  EXPECT_THAT(Lines(MeasuredLevelsCsv(measured))[0], HasSubstr(",force_N,force_std_N,"));
  measured.excitation_quantity = "voltage";
  EXPECT_THAT(Lines(MeasuredLevelsCsv(measured))[0], HasSubstr(",voltage_V,voltage_std_V,"));
}

TEST(MeasuredBackboneCsv, ALabelWithACommaStaysOneCell) {
  MeasuredBackbone measured = TwoLevels();
  measured.levels[0].label = "1,5 N \"up\"";
  const std::vector<std::string> lines = Lines(MeasuredLevelsCsv(measured));
  EXPECT_EQ(lines[1].rfind("\"1,5 N \"\"up\"\"\",force,50.1234568,", 0), 0u) << lines[1];
}

}  // namespace
}  // namespace beamid::solver
