// The report's numbers are rounded to their uncertainty: σ to two
// significant digits, the value to the same decimal place, a common power of
// ten for very small or large numbers, and no "± 0" for a σ that is zero or
// unknown; units are written with their symbols.
#include "solver/report/uncertain_number.h"

#include <cmath>
#include <limits>

#include <gtest/gtest.h>

namespace beamid::solver {
namespace {

TEST(UncertainNumber, RoundsTheValueToTheSecondSignificantDigitOfSigma) {
  EXPECT_EQ(WithUncertainty(150.4512, 0.0021), "150.4512 ± 0.0021");
  EXPECT_EQ(WithUncertainty(150.45167, 0.00214), "150.4517 ± 0.0021");
  EXPECT_EQ(WithUncertainty(0.05003, 0.000085), "0.050030 ± 0.000085");  // a trailing zero is a digit
  EXPECT_EQ(WithUncertainty(54.00537, 0.0312), "54.005 ± 0.031");
  EXPECT_EQ(WithUncertainty(-4.04, 4.3), "-4.0 ± 4.3");
  EXPECT_EQ(WithUncertainty(299992.3, 41.2), "299992 ± 41");
  EXPECT_EQ(WithUncertainty(299992.3, 412.0), "299990 ± 410");  // tens: σ's second digit is the tens
  EXPECT_EQ(WithUncertainty(0.0001, 0.01), "0.000 ± 0.010");    // not "-0.000" or "1e-04"
  EXPECT_EQ(WithUncertainty(-0.0001, 0.01), "0.000 ± 0.010");
}

TEST(UncertainNumber, ASigmaThatRoundsUpToAFurtherDigitKeepsTwoSignificantDigits) {
  EXPECT_EQ(WithUncertainty(1.23456, 0.0996), "1.23 ± 0.10");  // not "1.235 ± 0.100"
  EXPECT_EQ(WithUncertainty(12.0, 9.96), "12 ± 10");
}

TEST(UncertainNumber, VerySmallOrLargeNumbersShareOnePowerOfTen) {
  // Fixed notation holds up to 10⁵: a value known to 4.2·10⁻⁹ keeps its digits.
  EXPECT_EQ(WithUncertainty(0.078451234, 4.2e-9), "0.0784512340 ± 0.0000000042");
  EXPECT_EQ(WithUncertainty(1.9012e-4, 2.04e-5), "(1.90 ± 0.20)·10⁻⁴");
  EXPECT_EQ(WithUncertainty(2.1e-9, 3e-11), "(2.100 ± 0.030)·10⁻⁹");
  EXPECT_EQ(WithUncertainty(2.99992e7, 4.1e3), "(2.99992 ± 0.00041)·10⁷");
  const UncertainFormat format(1.9012e-4, 2.04e-5);
  EXPECT_EQ(format.Format(1.9012e-4), "1.90·10⁻⁴");
  EXPECT_EQ(format.Format(1.9012e-4 - 1.96 * 2.04e-5), "1.50·10⁻⁴");  // an interval bound, same place
}

TEST(UncertainNumber, ASigmaOfZeroOrNotFiniteIsNoSigma) {
  for (const double sigma :
       {0.0, -1.0, std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()}) {
    const std::string text = WithUncertainty(150.4512, sigma);
    EXPECT_EQ(text, "150.451 (σ not available)") << sigma;
    EXPECT_EQ(text.find("± 0"), std::string::npos);
    EXPECT_FALSE(UncertainFormat(150.4512, sigma).has_sigma());
  }
  EXPECT_EQ(WithUncertainty(2.99992e-7, 0.0), "2.99992·10⁻⁷ (σ not available)");
  EXPECT_EQ(UncertainFormat(1.0, 0.1).Format(std::nan("")), "—");
}

TEST(UncertainNumber, UnitsAreWrittenWithTheirSymbols) {
  EXPECT_EQ(WithUncertainty(150.4512, 0.0021, "N*m/rad"), "150.4512 ± 0.0021 N·m/rad");
  EXPECT_EQ(UnitSymbol("N*m*s/rad"), "N·m·s/rad");
  EXPECT_EQ(UnitSymbol("N*m/rad^3"), "N·m/rad³");
  EXPECT_EQ(UnitSymbol("m/s^2"), "m/s²");
  EXPECT_EQ(UnitSymbol("s^-1"), "s⁻¹");
  EXPECT_EQ(UnitSymbol("Hz"), "Hz");
  EXPECT_EQ(UnitSymbol("1"), "");
  EXPECT_EQ(WithUncertainty(0.0123, 0.0011, "1"), "0.0123 ± 0.0011");
}

}  // namespace
}  // namespace beamid::solver
