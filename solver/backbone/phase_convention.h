// Whether a level's phase runs through its resonance the way beamid's
// convention says it must (docs/fourier-convention.md, x(t) = Re(X e^{iωt})),
// so that a table written in another convention or from a sensor mounted
// upside down is said, not absorbed into a negative damping or modal constant.
//
// For one mode the receptance X_d/F = A/(ω_n² − ω² + 2iωζω_n): its phase
// falls by π through the resonance, from arg A to arg A − π, and is
// arg A − π/2 at the peak; a drive-point receptance (A > 0) runs 0 → −π, so
// a velocity (×iω) runs +π/2 → −π/2 and an acceleration (×(−ω²)) π → 0.
// Both are read on the phase's course over the steps near the mode (from
// the first to the last whose |X/F| reaches `window` of the largest), its
// midpoint standing for the peak's arg A − π/2.
//  - The phase rising through the resonance instead is the other sign
//    convention, e^{−iωt} (or the force's phase relative to the response, or
//    negative damping): "runs backwards".
//  - The phase falling but half a turn away from the drive-point's (for an
//    acceleration 0 → −π, a displacement's course) is a sign flip: a sensor
//    or force transducer mounted upside down — or a sensor beyond a node of
//    the mode, where A < 0 is real: "off by half a turn".
#pragma once

#include <complex>
#include <string>
#include <vector>

#include "signal/quantity.h"

namespace beamid::solver {

enum class PhaseCourse { kAsExpected, kOffByHalfATurn, kRunsBackwards, kUndecided };

struct PhaseConventionCheck {
  PhaseCourse course = PhaseCourse::kUndecided;
  double start_phase_rad = 0.0;  // in the level's quantity, at the first and last step of the window
  double end_phase_rad = 0.0;
  std::string message;  // with the numbers and the fix; "" when as expected or undecided
};

struct ReceptancePoint {
  double omega_rad_s = 0.0;
  std::complex<double> receptance_m_N;  // X_d/F
};

// `points` sorted by frequency, in displacement; `window`: the fraction of
// the peak |X_d/F| above which points show the resonance. Undecided when
// the phase turns by less than a quarter turn over them (no resonance crossed).
PhaseConventionCheck CheckPhaseConvention(const std::vector<ReceptancePoint>& points, signal::Quantity quantity,
                                          double window);

}  // namespace beamid::solver
