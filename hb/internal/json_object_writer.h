// Internal: the writing side of json_object_reader.h for the sections that
// scenarios and model files share (beam, support, attachments). One writer
// per shared reader, so that a field added to a section is added to both
// formats at once and their round-trip tests catch a writer that forgets it.
// Keys are written in the order the documentation lists them (ordered_json),
// so that a written file reads like the examples.
#pragma once

#include <cmath>
#include <optional>

#include <nlohmann/json.hpp>

#include "hb/beam_properties.h"
#include "hb/linear_attachments.h"
#include "hb/support_law.h"

namespace beamid::hb::internal {

using OrderedJson = nlohmann::ordered_json;

// Every field, also the ones ReadBeam would default: a scenario's nominal
// beam defaults to the true one, so only a complete beam reads back as written.
inline OrderedJson BeamToJson(const BeamProperties& beam) {
  OrderedJson out = OrderedJson::object();
  out["length_m"] = beam.length_m;
  out["width_m"] = beam.width_m;
  out["thickness_m"] = beam.thickness_m;
  out["youngs_modulus_Pa"] = beam.youngs_modulus_Pa;
  out["density_kg_m3"] = beam.density_kg_m3;
  out["loss_factor"] = beam.loss_factor;
  // Rayleigh damping only when there is some: the files of a beam without it read as before.
  if (beam.rayleigh_mass_1_s != 0.0) out["rayleigh_mass_1_s"] = beam.rayleigh_mass_1_s;
  if (beam.rayleigh_stiffness_s != 0.0) out["rayleigh_stiffness_s"] = beam.rayleigh_stiffness_s;
  return out;
}

// The inverse of ReadSupport: "jenkins" only when present and "one_sided"
// only when non-zero, as the reader's defaults are "none".
inline OrderedJson SupportToJson(const PolynomialSupportLaw::Coefficients& polynomial,
                                 const std::optional<JenkinsSupportLaw::Parameters_>& jenkins,
                                 double one_sided_stiffness_Nm_rad) {
  OrderedJson poly = OrderedJson::object();
  poly["k1_Nm_rad"] = polynomial.k1_Nm_rad;
  poly["k2_Nm_rad2"] = polynomial.k2_Nm_rad2;
  poly["k3_Nm_rad3"] = polynomial.k3_Nm_rad3;
  poly["c_Nms_rad"] = polynomial.c_Nms_rad;
  OrderedJson support = OrderedJson::object();
  support["polynomial"] = poly;
  if (jenkins) {
    OrderedJson j = OrderedJson::object();
    j["stiffness_Nm_rad"] = jenkins->stiffness_Nm_rad;
    j["slip_moment_Nm"] = jenkins->slip_moment_Nm;
    support["jenkins"] = j;
  }
  if (one_sided_stiffness_Nm_rad != 0.0) support["one_sided"] = {{"stiffness_Nm_rad", one_sided_stiffness_Nm_rad}};
  return support;
}

// The inverse of ReadAttachments. A rigid constraint is an infinite
// stiffness, which JSON cannot hold: it is left out, which the reader takes
// as rigid. An empty object when nothing is attached.
inline OrderedJson AttachmentsToJson(const LinearAttachments& attachments) {
  OrderedJson out = OrderedJson::object();
  if (std::isfinite(attachments.clamp_rotational_stiffness_Nm_rad))
    out["clamp_rotational_stiffness_Nm_rad"] = attachments.clamp_rotational_stiffness_Nm_rad;
  if (std::isfinite(attachments.support_translational_stiffness_N_m))
    out["support_translational_stiffness_N_m"] = attachments.support_translational_stiffness_N_m;
  if (!attachments.point_masses.empty()) {
    OrderedJson masses = OrderedJson::array();
    for (const PointMass& m : attachments.point_masses) {
      OrderedJson mass = OrderedJson::object();
      mass["position_m"] = m.position_m;
      mass["mass_kg"] = m.mass_kg;
      masses.push_back(mass);
    }
    out["point_masses"] = masses;
  }
  return out;
}

}  // namespace beamid::hb::internal
