// Frequency response curves by pseudo-arclength continuation of the harmonic
// balance equations R(z, ω) = 0 (hb/harmonic_balance.h).
//
// The path y(s) = (z, ω) is followed in scaled coordinates (z / z_ref,
// ω / ω_ref) so that amplitude and frequency weigh alike: a predictor along
// the tangent t (J_y·t = 0, |t| = 1, oriented like the previous tangent),
// then Newton on the bordered system [R(y) = 0; tᵀ(y − y_pred) = 0], which
// stays regular at turning points where ∂R/∂z is singular. The step adapts to
// the number of corrector iterations.
//
// Stability: for a forced response the sign of det(∂R/∂z) changes at every
// turning point (and only there for a branch without bifurcations), so a
// point is flagged stable when the sign equals that of the first point,
// which sits at low amplitude far from resonance and is stable. This is
// turning-point detection, not a Floquet analysis: it cannot see
// Neimark–Sacker or symmetry-breaking bifurcations.
#pragma once

#include <functional>
#include <vector>

#include <Eigen/Core>

#include "hb/harmonic_balance.h"

namespace beamid::hb {

struct ContinuationOptions {
  double omega_start_rad_s = 0.0;
  double omega_end_rad_s = 0.0;  // may be below the start (a down sweep)
  int max_points = 400;
  // Arclength steps in scaled coordinates (Δω/ω_ref ≈ step on a flat curve).
  double initial_step = 2e-3;
  double min_step = 1e-6;
  double max_step = 2e-2;
  int target_iterations = 4;   // steps grow below this count, shrink above
  int max_iterations = 12;
  double tolerance = 1e-9;     // corrector: scaled step norm

  // Throws InputError naming the field, its value and the allowed range.
  void Validate() const;
};

struct FrequencyResponsePoint {
  double omega_rad_s = 0.0;
  Eigen::VectorXcd theta_rad;  // Θ_0..Θ_H
  bool stable = true;
};

struct ContinuationSummary {
  std::vector<FrequencyResponsePoint> points;
  int num_turning_points = 0;
  bool reached_end = false;
  std::string message;
};

// Follows the response to the force phasors F_0..F_H [N] from omega_start to
// omega_end. `progress`, if given, is called with the fraction done.
ContinuationSummary TraceFrequencyResponse(const HarmonicBalance& balance, const Eigen::VectorXcd& force_N,
                                           const ContinuationOptions& options,
                                           const std::function<void(double)>& progress = {});

}  // namespace beamid::hb
