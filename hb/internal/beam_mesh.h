// Internal: the segmentation of the beam into exact dynamic-stiffness
// segments and the Krylov–Duncan transfer matrix of one segment.
//
// For w'''' = μ·w (μ = λ⁴, complex with a loss factor) the state
// s = [w, w', w'', w'''] is carried along a segment of length ℓ by
//     T(ℓ) = [[φ0, φ1, φ2, φ3], [μφ3, φ0, φ1, φ2], [μφ2, μφ3, φ0, φ1], [μφ1, μφ2, μφ3, φ0]],
// φ_m(ℓ) = Σ_n μⁿ ℓ^{4n+m}/(4n+m)!  (the Krylov functions S, T/λ, U/λ², V/λ³),
// which are entire in μ: no branch of λ needs choosing and ω = 0 is exact.
#pragma once

#include <array>
#include <complex>
#include <vector>

#include <Eigen/Core>

namespace beamid::hb {

using Complex = std::complex<double>;

struct BeamMesh {
  std::vector<double> node_positions_m;  // sorted, first 0, last L
  double bending_stiffness_Nm2 = 0.0;    // EI (real part)
  double loss_factor = 0.0;              // η: EI(1 + iη) in the frequency domain
  double mass_per_length_kg_m = 0.0;     // ρA
  double rayleigh_mass_1_s = 0.0;        // α: ρA·ω² becomes ρA·(ω² − iαω)
  double rayleigh_stiffness_s = 0.0;     // β: EI becomes EI·(1 + iη + iβω)

  int num_nodes() const { return static_cast<int>(node_positions_m.size()); }
  // Index of the segment that holds x (the last one for x = L).
  int SegmentOf(double position_m) const;
  // μ = λ⁴ = ρA(ω² − iαω) / (EI(1 + iη + iβω)) [1/m⁴]
  Complex Lambda4(double omega_rad_s) const;
  // EI(1 + iη + iβω) [N·m²]
  Complex ComplexBendingStiffness(double omega_rad_s) const {
    return {bending_stiffness_Nm2, bending_stiffness_Nm2 * (loss_factor + rayleigh_stiffness_s * omega_rad_s)};
  }
  // m·(ω² − iαω): a mass's (or ρA's) share of the dynamic stiffness, with sign reversed
  Complex Inertia(double mass, double omega_rad_s) const {
    return {mass * omega_rad_s * omega_rad_s, -mass * rayleigh_mass_1_s * omega_rad_s};
  }
};

// φ0..φ3 at length ℓ for μ.
std::array<Complex, 4> KrylovFunctions(Complex mu, double length_m);

// 4×4 transfer matrix T(ℓ) of the state [w, w', w'', w'''].
Eigen::Matrix4cd TransferMatrix(Complex mu, double length_m);

// Exact dynamic stiffness of one segment: maps the end displacements
// [w(0), w'(0), w(ℓ), w'(ℓ)] to the end loads [F(0), M(0), F(ℓ), M(ℓ)] that
// act on the segment in the directions of those displacements.
Eigen::Matrix4cd SegmentDynamicStiffness(Complex mu, Complex bending_stiffness_Nm2, double length_m);

// w^(derivative)(s) inside a segment from its end displacements.
Complex SegmentInterior(Complex mu, double length_m, const Eigen::Vector4cd& end_displacements, double s_m,
                        int derivative);

}  // namespace beamid::hb
