#include "solver/report/uncertain_number.h"

#include <algorithm>
#include <cmath>

#include <fmt/core.h>

namespace beamid::solver {
namespace {

// Plain fixed notation reads best for these magnitudes; beyond them a common
// power of ten keeps the digits few.
constexpr int kMinFixedExponent = -3;
constexpr int kMaxFixedExponent = 5;

// The superscript of a digit or sign ("" for '+'); null for anything else.
const char* Superscript(char c) {
  static constexpr const char* kDigits[] = {"⁰", "¹", "²", "³", "⁴", "⁵", "⁶", "⁷", "⁸", "⁹"};
  if (c >= '0' && c <= '9') return kDigits[c - '0'];
  if (c == '-') return "⁻";
  if (c == '+') return "";
  return nullptr;
}

// fmt writes -0.00 for a small negative number rounded to zero.
std::string WithoutNegativeZero(std::string text) {
  if (text.starts_with('-') && text.find_first_not_of("-0.") == std::string::npos) text.erase(0, 1);
  return text;
}

// Six significant digits, with ·10ⁿ instead of e-notation.
std::string SixDigits(double x) {
  if (!std::isfinite(x)) return "—";
  const double magnitude = std::abs(x);
  if (magnitude == 0.0 || (magnitude >= 1e-4 && magnitude < 1e6)) return fmt::format("{:.6g}", x);
  const int exponent = static_cast<int>(std::floor(std::log10(magnitude)));
  return fmt::format("{:.5f}", x / std::pow(10.0, exponent)) + PowerOfTen(exponent);
}

}  // namespace

std::string PowerOfTen(int exponent) {
  if (exponent == 0) return "";
  std::string out = "·10";
  for (const char c : std::to_string(exponent)) out += Superscript(c);
  return out;
}

UncertainFormat::UncertainFormat(double value, double sigma) {
  has_sigma_ = std::isfinite(sigma) && sigma > 0.0;
  if (!has_sigma_) return;
  // The decimal place of σ's second significant digit; σ = 0.0995 rounds to
  // 0.10, whose second digit is one place further left.
  int place = static_cast<int>(std::floor(std::log10(sigma))) - 1;
  if (std::round(sigma / std::pow(10.0, place)) >= 100.0) ++place;
  const double rounded_sigma = std::round(sigma / std::pow(10.0, place)) * std::pow(10.0, place);
  const double largest = std::isfinite(value) ? std::max(std::abs(value), rounded_sigma) : rounded_sigma;
  const int magnitude = static_cast<int>(std::floor(std::log10(largest)));
  if (magnitude < kMinFixedExponent || magnitude > kMaxFixedExponent) {
    exponent_ = magnitude;
    decimals_ = magnitude - place;
  } else {
    exponent_ = 0;
    decimals_ = -place;
  }
}

std::string UncertainFormat::Format(double x) const {
  if (!std::isfinite(x)) return "—";
  if (!has_sigma_) return SixDigits(x);
  const double mantissa = x / std::pow(10.0, exponent_);
  std::string text;
  if (decimals_ >= 0) {
    text = fmt::format("{:.{}f}", mantissa, decimals_);
  } else {
    const double step = std::pow(10.0, -decimals_);
    text = fmt::format("{:.0f}", std::round(mantissa / step) * step);
  }
  return WithoutNegativeZero(text) + PowerOfTen(exponent_);
}

std::string UncertainFormat::WithSigma(double value, double sigma) const {
  if (!has_sigma_) return SixDigits(value) + " (σ not available)";
  if (exponent_ == 0) return Format(value) + " ± " + Format(sigma);
  const UncertainFormat plain = [&] {
    UncertainFormat f = *this;
    f.exponent_ = 0;
    return f;
  }();
  const double scale = std::pow(10.0, exponent_);
  return "(" + plain.Format(value / scale) + " ± " + plain.Format(sigma / scale) + ")" + PowerOfTen(exponent_);
}

std::string NumberOrWhyNot(double x, std::string_view format, std::string_view why) {
  return std::isfinite(x) ? fmt::format(fmt::runtime(format), x) : "not estimated (" + std::string(why) + ")";
}

std::string UncertainOrWhyNot(double value, double sigma, std::string_view why) {
  return std::isfinite(value) ? WithUncertainty(value, sigma) : "not estimated (" + std::string(why) + ")";
}

std::string WithUncertainty(double value, double sigma, std::string_view unit) {
  const std::string symbol = UnitSymbol(unit);
  return UncertainFormat(value, sigma).WithSigma(value, sigma) + (symbol.empty() ? "" : " " + symbol);
}

std::string UnitSymbol(std::string_view unit) {
  if (unit == "1") return "";
  std::string out;
  for (std::size_t i = 0; i < unit.size(); ++i) {
    const char c = unit[i];
    if (c == '*') {
      out += "·";
    } else if (c == '^') {
      // The exponent's digits (and sign) as superscripts.
      std::size_t j = i + 1;
      std::string power;
      while (j < unit.size() && Superscript(unit[j]) != nullptr && (unit[j] != '-' || j == i + 1)) {
        power += Superscript(unit[j]);
        ++j;
      }
      if (power.empty()) {
        out += c;
      } else {
        out += power;
        i = j - 1;
      }
    } else {
      out += c;
    }
  }
  return out;
}

}  // namespace beamid::solver
