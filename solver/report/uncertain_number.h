// Numbers as the report prints them: a value rounded to its standard
// uncertainty σ (σ to two significant digits, the value to the same decimal
// place: 150.4512 ± 0.0021), with a common power of ten when the numbers are
// very small or very large ((2.100 ± 0.030)·10⁻⁹), and units written with
// their symbols (N·m/rad³, m/s²). A σ of zero or one that is not finite is
// no σ: the value keeps six significant digits and no "± 0" claims it exact.
#pragma once

#include <string>
#include <string_view>

namespace beamid::solver {

// How to print the numbers that go with one uncertain value (the value, its
// σ, its interval bounds): at σ's decimal place and with a common exponent.
class UncertainFormat {
 public:
  UncertainFormat(double value, double sigma);

  bool has_sigma() const { return has_sigma_; }
  // `x` at this format's decimal place (and exponent: "2.100·10⁻⁹"); without
  // a σ, six significant digits. "—" when x is not finite.
  std::string Format(double x) const;
  // "150.4512 ± 0.0021", "(2.100 ± 0.030)·10⁻⁹", "150.451 (σ unknown)".
  std::string WithSigma(double value, double sigma) const;

 private:
  bool has_sigma_ = false;
  int decimals_ = 6;  // of the mantissa; negative: rounded to tens, hundreds, …
  int exponent_ = 0;  // common power of ten, 0 when none
};

// value ± σ, rounded as UncertainFormat does, and the unit's symbol after it
// (none for a dimensionless "1" or an empty unit).
std::string WithUncertainty(double value, double sigma, std::string_view unit = {});

// `x` in `format` (fmt's, e.g. "{:.3g} %"), or "not estimated (why)" when
// it is not finite: a person reads a word and its reason, never "nan".
std::string NumberOrWhyNot(double x, std::string_view format, std::string_view why);
// WithUncertainty(value, sigma), or "not estimated (why)" when value is not finite.
std::string UncertainOrWhyNot(double value, double sigma, std::string_view why);

// A unit as the data files write it ("N*m*s/rad", "m/s^2", "1") with its
// symbols: "N·m·s/rad", "m/s²", "" (dimensionless).
std::string UnitSymbol(std::string_view unit);

// "·10⁻⁹": the power of ten in Unicode superscripts ("" for 0).
std::string PowerOfTen(int exponent);

}  // namespace beamid::solver
