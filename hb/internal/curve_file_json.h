// Internal: what the files of `beamid frc` and `beamid backbone` (frc_file.h,
// backbone_file.h) share: numbers that JSON may lack (null), phasor lists,
// the sensors of a point, and the CSV's number format.
#pragma once

#include <cmath>
#include <complex>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "hb/json_field.h"

namespace beamid::hb::internal {

using CurveJson = nlohmann::ordered_json;

// JSON has no NaN: a number that is not finite is null.
inline CurveJson JsonNumber(double v) { return std::isfinite(v) ? CurveJson(v) : CurveJson(nullptr); }

// [[re, im], ...], the JSON form of phasors everywhere in beamid.
inline CurveJson JsonPhasors(const std::vector<std::complex<double>>& phasors) {
  CurveJson out = CurveJson::array();
  for (const auto& p : phasors) out.push_back(CurveJson::array({JsonNumber(p.real()), JsonNumber(p.imag())}));
  return out;
}

inline std::vector<std::complex<double>> PhasorsFromJson(const JsonField& field) {
  std::vector<std::complex<double>> out;
  for (std::size_t i = 0; i < field.Size(); ++i) out.push_back(field.At(i).Phasor());
  return out;
}

// The channels of a point's "sensors" object, in the file's order.
// Two sensor positions of one file: equal, or both unknown (NaN).
inline bool SamePosition(double a, double b) { return a == b || (std::isnan(a) && std::isnan(b)); }

// The phasors k = 0..H of `field`, refused when there are not H + 1.
inline std::vector<std::complex<double>> HarmonicPhasors(const JsonField& field, int harmonics) {
  std::vector<std::complex<double>> out = PhasorsFromJson(field);
  if (out.size() != static_cast<std::size_t>(harmonics) + 1)
    field.Fail("must hold " + std::to_string(harmonics + 1) + " phasors (k = 0..harmonics), not " +
               std::to_string(out.size()));
  return out;
}

inline std::vector<std::string> SensorChannels(const JsonField& sensors) {
  std::vector<std::string> out;
  for (const auto& item : sensors.Object().json().items()) out.push_back(item.key());
  return out;
}

// A CSV number: nine significant digits.
inline std::string CsvNumber(double v) { return fmt::format("{:.9g}", v); }

}  // namespace beamid::hb::internal
