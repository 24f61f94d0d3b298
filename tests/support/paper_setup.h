// The paper's set-up as a test fixture: steel beam 600 × 40 × 5 mm,
// force at 0.570 m, accelerometers at 0.100, 0.300, 0.570 m.
#pragma once

#include <functional>

#include "hb/beam_properties.h"

namespace beamid::testing {

inline hb::BeamProperties PaperBeam() { return hb::BeamProperties{}; }
inline constexpr double kForcePosition_m = 0.570;
inline constexpr double kSensorPositions_m[] = {0.100, 0.300, 0.570};

// Bisection root of f on [a, b] (f(a), f(b) of opposite signs): an
// independent root finder for closed-form checks.
inline double Bisect(const std::function<double(double)>& f, double a, double b) {
  double fa = f(a);
  for (int i = 0; i < 200 && b - a > 1e-15 * b; ++i) {
    const double m = 0.5 * (a + b);
    const double fm = f(m);
    if ((fm < 0) == (fa < 0)) {
      a = m;
      fa = fm;
    } else {
      b = m;
    }
  }
  return 0.5 * (a + b);
}

}  // namespace beamid::testing
