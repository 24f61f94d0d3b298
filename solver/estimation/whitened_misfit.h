// A phasor residual in units of its uncertainty: L⁻¹·(Re e, Im e)ᵀ with L the
// Cholesky factor of the phasor's covariance (FitStep::whitening), so that
// its squared norm is the residual's χ² share (solver/estimation/fit_data.h).
#pragma once

#include <complex>
#include <cstddef>

#include <Eigen/Core>

#include "solver/estimation/fit_data.h"

namespace beamid::solver {

// e at channel c, harmonic k (1-based) of step s, whitened.
inline Eigen::Vector2d Whitened(const FitStep& s, int c, int k, std::complex<double> e) {
  return s.whitening[static_cast<std::size_t>(c)][static_cast<std::size_t>(k - 1)] *
         Eigen::Vector2d(e.real(), e.imag());
}

}  // namespace beamid::solver
