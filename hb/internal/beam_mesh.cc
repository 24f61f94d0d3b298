#include "hb/internal/beam_mesh.h"

#include <algorithm>
#include <cmath>

#include <Eigen/LU>

namespace beamid::hb {

int BeamMesh::SegmentOf(double position_m) const {
  const auto it = std::upper_bound(node_positions_m.begin(), node_positions_m.end(), position_m);
  const int index = static_cast<int>(it - node_positions_m.begin()) - 1;
  return std::clamp(index, 0, num_nodes() - 2);
}

Complex BeamMesh::Lambda4(double omega_rad_s) const {
  return Inertia(mass_per_length_kg_m, omega_rad_s) / ComplexBendingStiffness(omega_rad_s);
}

std::array<Complex, 4> KrylovFunctions(Complex mu, double length_m) {
  const double l = length_m;
  const Complex z4 = mu * (l * l * l * l);
  std::array<Complex, 4> phi;
  if (std::abs(z4) < 16.0) {
    // Series: the closed forms below cancel catastrophically for small λℓ.
    const double powers[4] = {1.0, l, l * l / 2.0, l * l * l / 6.0};
    for (int m = 0; m < 4; ++m) {
      Complex term = powers[m];
      Complex sum = term;
      for (int n = 0; n < 60; ++n) {
        const double a = 4.0 * n + m;
        term *= z4 / ((a + 1.0) * (a + 2.0) * (a + 3.0) * (a + 4.0));
        sum += term;
        if (std::abs(term) <= 1e-18 * std::abs(sum)) break;
      }
      phi[m] = sum;
    }
    return phi;
  }
  const Complex lambda = std::pow(mu, 0.25);
  const Complex z = lambda * l;
  const Complex ch = std::cosh(z), sh = std::sinh(z), c = std::cos(z), s = std::sin(z);
  phi[0] = 0.5 * (ch + c);
  phi[1] = 0.5 * (sh + s) / lambda;
  phi[2] = 0.5 * (ch - c) / (lambda * lambda);
  phi[3] = 0.5 * (sh - s) / (lambda * lambda * lambda);
  return phi;
}

Eigen::Matrix4cd TransferMatrix(Complex mu, double length_m) {
  const auto p = KrylovFunctions(mu, length_m);
  Eigen::Matrix4cd t;
  t << p[0], p[1], p[2], p[3],
       mu * p[3], p[0], p[1], p[2],
       mu * p[2], mu * p[3], p[0], p[1],
       mu * p[1], mu * p[2], mu * p[3], p[0];
  return t;
}

namespace {

// The end derivatives [w''(0), w'''(0)] that, with [w(0), w'(0)], reach the
// displacements [w(ℓ), w'(ℓ)]: f0 = T12⁻¹ (u_ℓ − T11 u0).
Eigen::Vector2cd StartCurvatureAndShear(const Eigen::Matrix4cd& t, const Eigen::Vector4cd& ends) {
  const Eigen::Vector2cd u0 = ends.head<2>();
  const Eigen::Vector2cd ul = ends.tail<2>();
  return t.topRightCorner<2, 2>().inverse() * (ul - t.topLeftCorner<2, 2>() * u0);
}

}  // namespace

Eigen::Matrix4cd SegmentDynamicStiffness(Complex mu, Complex bending_stiffness_Nm2, double length_m) {
  const Eigen::Matrix4cd t = TransferMatrix(mu, length_m);
  Eigen::Matrix4cd k;
  for (int j = 0; j < 4; ++j) {
    Eigen::Vector4cd ends = Eigen::Vector4cd::Zero();
    ends[j] = 1.0;
    Eigen::Vector4cd state0;
    state0 << ends.head<2>(), StartCurvatureAndShear(t, ends);
    const Eigen::Vector4cd statel = t * state0;
    // Loads on the segment, from the variation of ½∫EI w''² (docs/derivation.md).
    k(0, j) = bending_stiffness_Nm2 * state0[3];
    k(1, j) = -bending_stiffness_Nm2 * state0[2];
    k(2, j) = -bending_stiffness_Nm2 * statel[3];
    k(3, j) = bending_stiffness_Nm2 * statel[2];
  }
  return k;
}

Complex SegmentInterior(Complex mu, double length_m, const Eigen::Vector4cd& end_displacements, double s_m,
                        int derivative) {
  const Eigen::Matrix4cd t = TransferMatrix(mu, length_m);
  Eigen::Vector4cd state0;
  state0 << end_displacements.head<2>(), StartCurvatureAndShear(t, end_displacements);
  return (TransferMatrix(mu, s_m).row(derivative) * state0).value();
}

}  // namespace beamid::hb
