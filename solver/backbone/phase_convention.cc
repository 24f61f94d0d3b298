#include "solver/backbone/phase_convention.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include <fmt/core.h>

namespace beamid::solver {
namespace {

constexpr double kPi = std::numbers::pi;

// An angle in (−π, π].
double Wrap(double angle) { return std::remainder(angle, 2 * kPi); }

double Degrees(double rad) { return rad * 180 / kPi; }

}  // namespace

PhaseConventionCheck CheckPhaseConvention(const std::vector<ReceptancePoint>& points, signal::Quantity quantity,
                                          double window) {
  PhaseConventionCheck check;
  if (points.size() < 3) return check;
  int peak = 0;
  for (int i = 1; i < static_cast<int>(points.size()); ++i)
    if (std::abs(points[i].receptance_m_N) > std::abs(points[peak].receptance_m_N)) peak = i;
  const double top = std::abs(points[peak].receptance_m_N);
  int first = peak, last = peak;
  while (first > 0 && std::abs(points[first - 1].receptance_m_N) >= window * top) --first;
  while (last + 1 < static_cast<int>(points.size()) && std::abs(points[last + 1].receptance_m_N) >= window * top) ++last;
  // The phase unwrapped across the window (steps turn it by less than π).
  double phase = std::arg(points[first].receptance_m_N), turned = 0.0;
  for (int i = first + 1; i <= last; ++i) {
    const double step = Wrap(std::arg(points[i].receptance_m_N) - std::arg(points[i - 1].receptance_m_N));
    turned += step;
  }
  // The level's own quantity: × (iω)^order adds order·π/2.
  const double shift = signal::DerivativeOrder(quantity) * kPi / 2;
  check.start_phase_rad = Wrap(phase + shift);
  check.end_phase_rad = check.start_phase_rad + turned;
  if (std::abs(turned) < kPi / 4) return check;
  // The drive-point course in this quantity: from `shift` to shift − π.
  const std::string name(signal::QuantityName(quantity));
  const std::string expected = fmt::format("{:+.0f}° → {:+.0f}°", Degrees(Wrap(shift)), Degrees(Wrap(shift)) - 180);
  const std::string measured =
      fmt::format("{:+.0f}° → {:+.0f}°", Degrees(check.start_phase_rad), Degrees(check.end_phase_rad));
  if (turned > 0) {
    check.course = PhaseCourse::kRunsBackwards;
    check.message = fmt::format(
        "the {}'s phase rises through the resonance ({}); in beamid's convention, x(t) = Re(X e^(iωt)), it falls "
        "(a drive point: {}): the table's phase is of the other convention (e^(−iωt)) or is the force's relative to "
        "the response — negate the phase column — or the damping is negative",
        name, measured, expected);
    return check;
  }
  // Halfway along its course the receptance's phase is arg A − π/2: within
  // a quarter turn of −π/2 for A > 0 (a complex mode turns A by much less).
  // Not the phase at the largest |X/F|: on a folded sweep that is the fold's
  // edge, below the backbone after a down-sweep's jump, where the phase has
  // barely begun to fall.
  const double halfway = std::arg(points[first].receptance_m_N) + turned / 2;
  if (std::cos(halfway + kPi / 2) < 0) {
    check.course = PhaseCourse::kOffByHalfATurn;
    check.message = fmt::format(
        "the {}'s phase runs {} through the resonance, half a turn from a drive point's {}: a sensor or force "
        "transducer mounted upside down (or a sign flipped in the acquisition) — or a sensor beyond a node of the "
        "mode, where the modal constant is negative",
        name, measured, expected);
    return check;
  }
  check.course = PhaseCourse::kAsExpected;
  return check;
}

}  // namespace beamid::solver
