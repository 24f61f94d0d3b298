// Internal: what the files of `beamid frc` and `beamid backbone` (frc_file.h,
// backbone_file.h) share: the rule that every point names the same sensors,
// and the CSV's number format.
#pragma once

#include <cmath>
#include <string>
#include <vector>

#include <fmt/format.h>

namespace beamid::hb::internal {

// Two sensor positions of one file: equal, or both unknown (NaN).
inline bool SamePosition(double a, double b) { return a == b || (std::isnan(a) && std::isnan(b)); }

// Where a point's sensors (each with .channel and .position_m) differ from
// the first point's, below the point: "sensors" for other names or another
// order, "sensors.<channel>.position_m" for another position; "" where they
// agree.
template <typename Sensor>
std::string OtherSensors(const std::vector<Sensor>& first, const std::vector<Sensor>& these) {
  if (these.size() != first.size()) return "sensors";
  for (std::size_t i = 0; i < these.size(); ++i)
    if (these[i].channel != first[i].channel) return "sensors";
  for (std::size_t i = 0; i < these.size(); ++i)
    if (!SamePosition(these[i].position_m, first[i].position_m)) return "sensors." + these[i].channel + ".position_m";
  return {};
}

// A CSV number: nine significant digits.
inline std::string CsvNumber(double v) { return fmt::format("{:.9g}", v); }

}  // namespace beamid::hb::internal
