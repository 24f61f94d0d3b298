// The uncertainty with which a fit must weigh a measured response phasor
// Y_k (harmonic k of one channel at one step), as the sum of what is
// independent in it:
//
//   Cov(Y_k) = Cov_noise                 the record's noise (signal/: the
//                                        phasor's own covariance)
//            + (k·u_F)²·y·yᵀ             the force: the model is driven with
//                                        the measured |F_1|, whose relative
//                                        error u_F = σ(|F_1|)/|F_1| moves Y_k
//                                        as |F_1|^k does at leading order
//            + σ_ω²·g·gᵀ                 the excitation frequency estimated
//                                        from the record, g = ∂Y_k/∂ω
//            + (ε·|Y_k|)²·I              the model's own error (finite
//                                        elements, harmonic truncation), ε
//                                        relative to the phasor itself
//
// y = (Re, Im) of Y_k. g comes from the measured values of the step and its
// neighbours on its level in acquisition order, through 1/Y: the inverse of
// a resonance's response, (ω_r² − ω² + iωb)/A for one linear mode, is a
// parabola in ω however sharp the peak, where Y itself changes faster than
// steps wider than the half-power band can follow.
//   g = −Y²·d(1/Y)/dω,  d(1/Y)/dω from the parabola through the three steps
//   (the chord at the ends of a level).
// A phasor within ten σ of its noise has no parabola worth the name (1/Y
// of noise): the smaller of its one-sided differences stands in.
// Across a jump the parabola is no derivative: g, and with it σ, is too
// large for the step or two beside the jump.

// The first two inputs are errors in the variables the model is driven
// with: weighed by its noise alone, the fundamental read χ² 1.2–2.4 times
// its degrees of freedom per channel and level on the paper's campaign,
// data whose physics the model holds.
#pragma once

#include <complex>
#include <vector>

#include <Eigen/Core>

namespace beamid::solver {

// Standard uncertainties (σ of the real and imaginary parts, rms of the
// two) of one phasor, term by term.
struct PhasorUncertaintyBudget {
  double noise = 0.0;
  double force = 0.0;
  double frequency = 0.0;
  double model_error = 0.0;
};

struct MeasuredPhasor {
  std::complex<double> value;
  Eigen::Matrix2d noise_covariance;
};

// The covariance of the phasor's real and imaginary parts with every term
// above, and its budget. neighbour_slope is g (0 where the step has no
// neighbour on its level); numerical_floor_std keeps noise-free data
// (simulations without noise) from getting an infinite weight.
Eigen::Matrix2d PhasorCovariance(const MeasuredPhasor& phasor, int harmonic, double force_relative_std,
                                 std::complex<double> neighbour_slope, double omega_std_rad_s,
                                 double relative_model_error, double numerical_floor_std,
                                 PhasorUncertaintyBudget* budget);

// g = ∂Y/∂ω at step i of a level (omega, values and their noise σ of that
// level's steps in acquisition order), as above; 0 where no neighbour lies
// at another frequency.
std::complex<double> NeighbourSlope(const std::vector<double>& omega_rad_s,
                                    const std::vector<std::complex<double>>& values,
                                    const std::vector<double>& noise_std, std::size_t i);

}  // namespace beamid::solver
