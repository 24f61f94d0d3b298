// The backbone (amplitude-dependent resonance frequency) of the beam with its
// nonlinear support, from the exact harmonic balance.
//
// Defined by phase resonance, as it is measured: for each amplitude a of the
// first harmonic of θ, the frequency ω and force level F at which θ's first
// harmonic lags the force's by 90°. With force phasors F·f̂_k (f̂_1 = 1, real),
// the unknowns are the harmonics Θ_0, Θ_2..Θ_H, ω and F, and the equations
// R(Θ, ω, F) = 0 with Θ_1 = −i·a fixed (a > 0; F may come out negative when
// the force and the support rotation act in opposite senses). For a
// conservative law the force tends to zero and this is the nonlinear normal
// mode's backbone; with dissipation F is the force that balances it.
#pragma once

#include <functional>
#include <vector>

#include <Eigen/Core>

#include "hb/harmonic_balance.h"

namespace beamid::hb {

struct BackboneOptions {
  double min_theta_amplitude_rad = 1e-5;
  double max_theta_amplitude_rad = 2e-2;
  int num_points = 200;
  bool geometric_spacing = true;  // amplitudes equally spaced in log

  // Throws InputError naming the field, its value and the allowed range.
  void Validate() const;
};

struct BackbonePoint {
  double theta_amplitude_rad = 0.0;
  double omega_rad_s = 0.0;
  double force_amplitude_N = 0.0;  // signed, see above
  Eigen::VectorXcd theta_rad;      // Θ_0..Θ_H
};

struct BackboneSummary {
  std::vector<BackbonePoint> points;
  bool complete = false;
  std::string message;
};

// `force_shape` f̂_0..f̂_H: the force's harmonic content relative to its
// fundamental (empty = a pure sine).
BackboneSummary TraceBackbone(const HarmonicBalance& balance, const BackboneOptions& options,
                              const Eigen::VectorXcd& force_shape = {},
                              const std::function<void(double)>& progress = {});

}  // namespace beamid::hb
