// Wilson's score interval at 95 % for a rate measured as `count` successes
// in `n` independent draws: the benchmarks' false-alarm and detection rates.
#pragma once

#include <algorithm>
#include <cmath>

namespace beamid::testing {

struct RateInterval {
  double rate = 0.0, low = 0.0, high = 1.0;
};

inline RateInterval WilsonInterval(int count, int n) {
  constexpr double z = 1.959963984540054;
  const double p = static_cast<double>(count) / n, z2n = z * z / n;
  const double centre = (p + 0.5 * z2n) / (1.0 + z2n);
  const double half = z / (1.0 + z2n) * std::sqrt(p * (1.0 - p) / n + 0.25 * z2n / n);
  return {p, std::max(0.0, centre - half), std::min(1.0, centre + half)};
}

}  // namespace beamid::testing
