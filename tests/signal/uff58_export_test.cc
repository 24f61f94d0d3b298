// A level written as a universal file (signal/uff58_export.h): read back by
// the stepped-sine reader to the digits it writes, in the fixed columns of
// the format, with labels a fixed-width field can hold; a base-excited level
// refused.
#include "signal/uff58_export.h"

#include <complex>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "signal/input_error.h"
#include "signal/phasor_table.h"
#include "signal/uff58_level.h"

namespace beamid::signal {
namespace {

std::vector<std::string> LinesOf(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

TEST(Uff58Export, ALevelReadsBackToTheDigitsItWrites) {
  const FirstHarmonicLevel table = ReadPhasorTable("examples/phasor_tables/high.csv");
  const std::string text = Uff58LevelText(table);
  const FirstHarmonicLevel back = FirstHarmonicLevelFromUff58(
      ParseUff58(text, "high.uff", Uff58Functions::kFrequencyFunctions), "high.uff", "high");
  ASSERT_EQ(back.points.size(), table.points.size());
  EXPECT_EQ(back.response_quantity, table.response_quantity);
  EXPECT_EQ(back.channel, table.channel.substr(0, 80));
  for (std::size_t i = 0; i < table.points.size(); ++i) {
    const auto& a = back.points[i];
    const auto& b = table.points[i];
    EXPECT_NEAR(a.frequency_hz, b.frequency_hz, 1e-12 * b.frequency_hz);  // E20.12: 13 digits
    EXPECT_NEAR(std::abs(a.force.value - b.force.value), 0.0, 1e-12 * std::abs(b.force.value));
    EXPECT_NEAR(std::abs(a.response.value - b.response.value), 0.0, 1e-11 * std::abs(b.response.value)) << i;
  }
}

TEST(Uff58Export, HeaderRecordsKeepTheirColumnsWhateverTheLabel) {
  FirstHarmonicLevel level = ReadPhasorTable("examples/phasor_tables/low.csv");
  level.label = "1,5 N — très haut, a label longer than any field of the format can hold at all, really";
  level.channel = "acc2 (Röhre)";
  const std::vector<std::string> lines = LinesOf(Uff58LevelText(level));
  int records_6 = 0;
  for (std::size_t i = 0; i < lines.size(); ++i) {
    EXPECT_LE(lines[i].size(), 80u) << i << ": " << lines[i];
    for (const unsigned char c : lines[i]) EXPECT_TRUE(c >= 0x20 && c <= 0x7e) << i << ": " << lines[i];
    if (i >= 6 && lines[i - 6] == "    58") {
      // Record 6: Format(2(I5,I10),2(1X,A10,I10,I4)), the function type in columns 1-5.
      ++records_6;
      EXPECT_EQ(lines[i].size(), 80u);
      const int type = std::stoi(lines[i].substr(0, 5));
      EXPECT_TRUE(type == 12 || type == 4) << lines[i];
    }
  }
  EXPECT_EQ(records_6, 2);
}

TEST(Uff58Export, ABaseExcitedLevelIsRefused) {
  FirstHarmonicLevel level = ReadPhasorTable("examples/phasor_tables/low.csv");
  level.excitation_quantity = Quantity::kBaseAcceleration;
  EXPECT_THROW(Uff58LevelText(level), InputError);
}

}  // namespace
}  // namespace beamid::signal
