// Finite-element model of the test beam for the time-domain simulator: Hermite
// cubic Euler–Bernoulli elements (two DOFs per node, deflection y and slope
// y'), consistent mass. The element matrices of length l are the classical
//     K_e = EI/l³ [12 6l −12 6l; 6l 4l² −6l 2l²; −12 −6l 12 −6l; 6l 2l² −6l 4l²]
//     M_e = ρAl/420 [156 22l 54 −13l; 22l 4l² 13l −3l²; 54 13l 156 −22l; −13l −3l² −22l 4l²]
// assembled into K·q̈-free form M·q̈ + K·q = f. Nodes are placed at every
// requested position (force, sensors, hidden positions, point masses) and the
// mesh is refined so that no element is longer than L / min_elements.
//
// Boundary conditions (docs/simulator.md): y(0) = 0; y'(0) = 0 unless the
// clamp has a finite rotational stiffness (then a spring on y'(0)); y(L) = 0
// unless the support has a finite translational stiffness (then a spring on
// y(L)). The slope θ = y'(L) is always free: the support law acts there, and
// it is NOT part of K (the simulator applies it). Point masses are added to the
// deflection DOF of their node.
#pragma once

#include <span>
#include <vector>

#include <Eigen/Core>

#include "hb/beam_properties.h"
#include "hb/linear_attachments.h"

namespace beamid::hb {

struct FeBeamOptions {
  // The mesh has at least this many elements (more when requested nodes force
  // shorter ones). The frequency error of cubic elements falls as h⁴: 20
  // elements put the first resonance ~1e-6 high, which a fit of a 3-level
  // campaign resolves (k1 came out 3e-5 high, 1–2 of its standard
  // deviations); 40 make that 16 times smaller.
  int min_elements = 40;

  // Throws InputError naming the field, its value and the allowed range.
  void Validate() const;
};

class FeBeam {
 public:
  // Marks a position whose deflection is identically zero (a constrained DOF).
  static constexpr int kConstrained = -1;

  // required_nodes_m: positions in [0, L] that must be nodes. Throws
  // std::invalid_argument for a position outside the beam or invalid
  // properties.
  FeBeam(const BeamProperties& beam, const LinearAttachments& attachments,
         std::span<const double> required_nodes_m, const FeBeamOptions& options = {});

  int NumDofs() const { return static_cast<int>(stiffness_.rows()); }
  int NumElements() const { return static_cast<int>(node_positions_m_.size()) - 1; }
  const std::vector<double>& node_positions_m() const { return node_positions_m_; }

  // Linear stiffness (beam + attachment springs, without the support law) and
  // mass (beam + point masses) on the free DOFs [N/m, N, N·m], [kg, kg·m, ...].
  const Eigen::MatrixXd& Stiffness() const { return stiffness_; }
  const Eigen::MatrixXd& Mass() const { return mass_; }

  // Free DOF of the deflection at a node position (matched to 1e-9 m), or
  // kConstrained. Throws std::invalid_argument if the position is not a node.
  int DeflectionDof(double position_m) const;
  // Free DOF of θ = y'(L), where the support law acts.
  int SupportRotationDof() const { return support_rotation_dof_; }

  // Undamped natural frequencies [rad/s] (ascending, the first `count`) with a
  // linear rotational spring of the given stiffness at x = L.
  std::vector<double> NaturalFrequencies_rad_s(int count, double support_stiffness_Nm_rad) const;

 private:
  int NodeIndex(double position_m) const;

  std::vector<double> node_positions_m_;
  std::vector<int> deflection_dof_;  // per node, or kConstrained
  int support_rotation_dof_ = 0;
  Eigen::MatrixXd stiffness_;
  Eigen::MatrixXd mass_;
};

}  // namespace beamid::hb
