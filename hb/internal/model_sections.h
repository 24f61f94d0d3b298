// Internal: the declarations (hb/json_schema.h) of the sections that model
// files and scenarios share: the beam, the support law and the linear
// attachments. One declaration per section, so that a field added to a
// section is added to both formats' writers, readers and documentation at
// once.
#pragma once

#include <cmath>

#include "hb/beam_properties.h"
#include "hb/input_limits.h"
#include "hb/json_schema.h"
#include "hb/linear_attachments.h"
#include "hb/support_law.h"

namespace beamid::hb::internal {

// "beam": length_m, width_m, thickness_m, youngs_modulus_Pa, density_kg_m3
// (required unless `dimensions` says optional: a scenario's nominal beam
// defaults to the true one), loss_factor, rayleigh_mass_1_s and
// rayleigh_stiffness_s (optional, 0 = none). BeamProperties::Validate
// checks the dimensions against one another once read.
template <typename Io, typename Beam>
void DescribeBeam(Io& io, Beam& beam, schema::Presence dimensions) {
  using schema::kOptional;
  io.Number("length_m", beam.length_m, "m", schema::Positive(), dimensions);
  io.Number("width_m", beam.width_m, "m", schema::Positive(), dimensions);
  io.Number("thickness_m", beam.thickness_m, "m", schema::Positive(), dimensions);
  io.Number("youngs_modulus_Pa", beam.youngs_modulus_Pa, "Pa", schema::Between(1e6, 1e13), dimensions);
  io.Number("density_kg_m3", beam.density_kg_m3, "kg/m³", schema::Between(1.0, 1e5), dimensions);
  io.Number("loss_factor", beam.loss_factor, "1", schema::Between(0.0, 1.0), kOptional);
  io.Check(beam.loss_factor < 1.0, "loss_factor < 1", "loss_factor");
  // Rayleigh damping only when there is some: the files of a beam without it read as before.
  if (schema::Writes(io, beam.rayleigh_mass_1_s != 0.0))
    io.Number("rayleigh_mass_1_s", beam.rayleigh_mass_1_s, "1/s", schema::Between(0.0, 1e4), kOptional);
  if (schema::Writes(io, beam.rayleigh_stiffness_s != 0.0))
    io.Number("rayleigh_stiffness_s", beam.rayleigh_stiffness_s, "s", schema::Between(0.0, 1.0), kOptional);
}

// "support": {"polynomial": {k1_Nm_rad, k2_Nm_rad2, k3_Nm_rad3, c_Nms_rad},
//             "jenkins": {stiffness_Nm_rad, slip_moment_Nm},
//             "one_sided": {stiffness_Nm_rad}}: jenkins only when present,
// one_sided only when non-zero (the reader's "none").
template <typename Io, typename Polynomial, typename Jenkins, typename Stiffness>
void DescribeSupport(Io& io, Polynomial& polynomial, Jenkins& jenkins, Stiffness& one_sided_stiffness_Nm_rad) {
  using schema::kOptional;
  using schema::Presence;
  io.Object("polynomial", polynomial, Presence::kRequired, [](auto& p, auto& c) {
    p.Number("k1_Nm_rad", c.k1_Nm_rad, "N m/rad", schema::NonNegative());  // required: a support without it is a typo
    p.Number("k2_Nm_rad2", c.k2_Nm_rad2, "N m/rad²", schema::Any(), kOptional);
    p.Number("k3_Nm_rad3", c.k3_Nm_rad3, "N m/rad³", schema::Any(), kOptional);
    p.Number("c_Nms_rad", c.c_Nms_rad, "N m s/rad", schema::NonNegative(), kOptional);
  });
  io.Object("jenkins", jenkins, kOptional, [](auto& j, auto& p) {
    j.Number("stiffness_Nm_rad", p.stiffness_Nm_rad, "N m/rad", schema::Positive());
    j.Number("slip_moment_Nm", p.slip_moment_Nm, "N m", schema::Positive());
  });
  if (schema::Writes(io, one_sided_stiffness_Nm_rad != 0.0))
    io.Object("one_sided", one_sided_stiffness_Nm_rad, kOptional,
              [](auto& o, auto& k) { o.Number("stiffness_Nm_rad", k, "N m/rad"); });
  io.Check(polynomial.k1_Nm_rad + one_sided_stiffness_Nm_rad >= 0.0,
           "polynomial.k1_Nm_rad + one_sided.stiffness_Nm_rad ≥ 0 (not a support that pushes)",
           "one_sided.stiffness_Nm_rad");
}

// "attachments": {clamp_rotational_stiffness_Nm_rad,
// support_translational_stiffness_N_m, point_masses: [{position_m, mass_kg}]},
// all optional. A rigid constraint is an infinite stiffness, which JSON
// cannot hold: it is left out, which the reader takes as rigid.
template <typename Io, typename Attachments>
void DescribeAttachments(Io& io, Attachments& a) {
  using schema::kOptional;
  if (schema::Writes(io, std::isfinite(a.clamp_rotational_stiffness_Nm_rad)))
    io.Number("clamp_rotational_stiffness_Nm_rad", a.clamp_rotational_stiffness_Nm_rad, "N m/rad", schema::Positive(),
              kOptional);
  if (schema::Writes(io, std::isfinite(a.support_translational_stiffness_N_m)))
    io.Number("support_translational_stiffness_N_m", a.support_translational_stiffness_N_m, "N/m",
              schema::Positive(), kOptional);
  if (schema::Writes(io, !a.point_masses.empty()))
    io.List("point_masses", a.point_masses, kMaxPointsOnBeam, kOptional, [](auto& m, auto& p) {
      m.Number("position_m", p.position_m, "m", schema::NonNegative(), kOptional);
      m.Number("mass_kg", p.mass_kg, "kg", schema::Positive());
    });
}

}  // namespace beamid::hb::internal
