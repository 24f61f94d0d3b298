// A CSV cell (hb/csv_cell.h): a number not finite is an empty cell, a finite
// one is printed in its format; a text is quoted only when it holds a comma,
// a quote or a line break, its quotes doubled, as RFC 4180 and spreadsheets
// read it back.
#include "hb/csv_cell.h"

#include <cmath>

#include <gtest/gtest.h>

namespace beamid::hb {
namespace {

TEST(CsvCell, ANumberIsPrintedOnlyWhenFinite) {
  EXPECT_EQ(CsvNumber(1.5, "{:.3g}"), "1.5");
  EXPECT_EQ(CsvNumber(-2.0e-9, "{:.9g}"), "-2e-09");
  EXPECT_EQ(CsvNumber(INFINITY, "{:.3g}"), "");
  EXPECT_EQ(CsvNumber(-INFINITY, "{:.3g}"), "");
  EXPECT_EQ(CsvNumber(NAN, "{:.3g}"), "");
}

TEST(CsvCell, ATextIsQuotedOnlyWhenItWouldSplitTheRow) {
  EXPECT_EQ(CsvText("low"), "low");
  EXPECT_EQ(CsvText("k1 [N·m/rad]"), "k1 [N·m/rad]");
  EXPECT_EQ(CsvText("1,5 N"), "\"1,5 N\"");
  EXPECT_EQ(CsvText("say \"up\""), "\"say \"\"up\"\"\"");
  EXPECT_EQ(CsvText("two\nlines"), "\"two\nlines\"");
  EXPECT_EQ(CsvText(""), "");
}

}  // namespace
}  // namespace beamid::hb
