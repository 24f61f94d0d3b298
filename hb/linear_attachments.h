// Linear elements attached to the beam besides the support law: a rotational
// spring at the clamp (clamp compliance), a translational spring at the
// support (a support that is not rigid laterally), and point masses
// (accelerometers, the shaker's moving parts). Infinite stiffness means an
// ideal constraint, which is the nominal set-up: y(0) = y'(0) = 0, y(L) = 0.
#pragma once

#include <limits>
#include <vector>

namespace beamid::hb {

struct PointMass {
  double position_m = 0.0;
  double mass_kg = 0.0;
};

struct LinearAttachments {
  static constexpr double kRigid = std::numeric_limits<double>::infinity();
  // Rotational stiffness of the clamp at x = 0 [N·m/rad]; kRigid = ideal clamp.
  double clamp_rotational_stiffness_Nm_rad = kRigid;
  // Lateral stiffness of the support at x = L [N/m]; kRigid = y(L) = 0.
  double support_translational_stiffness_N_m = kRigid;
  std::vector<PointMass> point_masses;
};

}  // namespace beamid::hb
