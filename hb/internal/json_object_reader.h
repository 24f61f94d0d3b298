// Internal: strict reading of JSON objects for beamid's input files. Every
// error names the file, the field's path and what to fix, and a field nobody
// asked for is an error, so a typo never falls back silently to a default.
#pragma once

#include <cmath>
#include <exception>
#include <optional>
#include <set>
#include <stdexcept>
#include <string>

#include <nlohmann/json.hpp>

#include "hb/beam_properties.h"
#include "hb/input_limits.h"
#include "hb/linear_attachments.h"
#include "hb/support_law.h"

namespace beamid::hb::internal {

using Json = nlohmann::json;

// Reads the fields of one JSON object, naming file and path in every error,
// and rejects fields it was not asked about.
class ObjectReader {
 public:
  // format_doc: where the user reads the file format, named in errors.
  ObjectReader(const Json& object, std::string source, std::string path,
               std::string format_doc = "docs/simulator.md")
      : object_(object), source_(std::move(source)), path_(std::move(path)), format_doc_(std::move(format_doc)) {
    if (!object_.is_object()) Fail("must be a JSON object");
  }
  ObjectReader(const ObjectReader&) = delete;
  ~ObjectReader() noexcept(false) {
    if (std::uncaught_exceptions() > 0) return;
    for (const auto& [key, value] : object_.items())
      if (!read_.count(key)) Fail("has an unknown field '" + key + "' (see " + format_doc_ + ")");
  }

  bool Has(const std::string& key) const { return object_.contains(key); }
  // Accepts a field that this reader deliberately does not use.
  void Ignore(const std::string& key) { read_.insert(key); }
  const Json& Raw(const std::string& key) {
    read_.insert(key);
    if (!object_.contains(key)) Fail("needs the field '" + key + "'");
    return object_.at(key);
  }
  double Number(const std::string& key) {
    const Json& v = Raw(key);
    if (!v.is_number() || !std::isfinite(v.get<double>())) FailField(key, "must be a finite number");
    return v.get<double>();
  }
  double Number(const std::string& key, double fallback) { return Has(key) ? Number(key) : (read_.insert(key), fallback); }
  double Positive(const std::string& key, double fallback) {
    const double v = Number(key, fallback);
    if (!(v > 0.0)) FailField(key, "must be positive");
    return v;
  }
  double NonNegative(const std::string& key, double fallback) {
    const double v = Number(key, fallback);
    if (!(v >= 0.0)) FailField(key, "must not be negative");
    return v;
  }
  std::string String(const std::string& key, const std::string& fallback) {
    read_.insert(key);
    if (!Has(key)) return fallback;
    if (!object_.at(key).is_string()) FailField(key, "must be a string");
    std::string text = object_.at(key).get<std::string>();
    // Names and labels end up in file names, CSV columns, plot titles and
    // reports, where a line break or another control character has no place.
    for (std::size_t i = 0; i < text.size(); ++i) {
      const auto byte = static_cast<unsigned char>(text[i]);
      if (byte < 0x20 || byte == 0x7F)
        FailField(key, "holds a control character (byte " + std::to_string(byte) + " at position " +
                           std::to_string(i + 1) + ": a line break, tab or the like). Fix: write it without line "
                           "breaks, tabs or other control characters");
    }
    return text;
  }
  bool Bool(const std::string& key, bool fallback) {
    read_.insert(key);
    if (!Has(key)) return fallback;
    if (!object_.at(key).is_boolean()) FailField(key, "must be true or false");
    return object_.at(key).get<bool>();
  }
  const Json& Array(const std::string& key) {
    const Json& v = Raw(key);
    if (!v.is_array()) FailField(key, "must be a JSON array");
    return v;
  }
  // A list of points on the beam (sensors, point masses), bounded.
  const Json& PointList(const std::string& key) {
    const Json& v = Array(key);
    if (v.size() > static_cast<std::size_t>(kMaxPointsOnBeam))
      FailField(key, "lists " + std::to_string(v.size()) + " points, more than the " +
                         std::to_string(kMaxPointsOnBeam) + " a beam model takes. Fix: give at most " +
                         std::to_string(kMaxPointsOnBeam) + " (see " + format_doc_ + ")");
    return v;
  }
  std::string PathOf(const std::string& key) const { return path_.empty() ? key : path_ + "." + key; }
  const std::string& source() const { return source_; }

  [[noreturn]] void FailField(const std::string& key, const std::string& what) const {
    throw std::invalid_argument(source_ + ": " + PathOf(key) + " " + what);
  }
  [[noreturn]] void Fail(const std::string& what) const {
    throw std::invalid_argument(source_ + ": " + (path_.empty() ? "the file" : path_) + " " + what);
  }

 private:
  const Json& object_;
  std::string source_;
  std::string path_;
  std::string format_doc_;
  std::set<std::string> read_;
};

inline void ReadBeam(ObjectReader& r, BeamProperties& beam, bool all_required) {
  auto field = [&](const char* key, double& value) {
    if (all_required) {
      value = r.Number(key);  // throws, naming the field, when it is missing
      if (!(value > 0.0)) r.FailField(key, "must be positive");
    } else if (r.Has(key)) {
      value = r.Positive(key, value);
    }
  };
  field("length_m", beam.length_m);
  field("width_m", beam.width_m);
  field("thickness_m", beam.thickness_m);
  field("youngs_modulus_Pa", beam.youngs_modulus_Pa);
  field("density_kg_m3", beam.density_kg_m3);
  beam.loss_factor = r.NonNegative("loss_factor", beam.loss_factor);
  beam.rayleigh_mass_1_s = r.NonNegative("rayleigh_mass_1_s", beam.rayleigh_mass_1_s);
  beam.rayleigh_stiffness_s = r.NonNegative("rayleigh_stiffness_s", beam.rayleigh_stiffness_s);
}


// "support": {"polynomial": {k1_Nm_rad, k2_Nm_rad2, k3_Nm_rad3, c_Nms_rad},
//             "jenkins": {stiffness_Nm_rad, slip_moment_Nm},
//             "one_sided": {stiffness_Nm_rad}} (jenkins and one_sided optional).
inline void ReadSupport(ObjectReader& top, const std::string& format_doc, PolynomialSupportLaw::Coefficients& polynomial,
                        std::optional<JenkinsSupportLaw::Parameters_>& jenkins, double& one_sided_stiffness_Nm_rad) {
  ObjectReader support(top.Raw("support"), top.source(), "support", format_doc);
  ObjectReader poly(support.Raw("polynomial"), top.source(), "support.polynomial", format_doc);
  polynomial.k1_Nm_rad = poly.Number("k1_Nm_rad");  // required: a support without it is a typo
  if (polynomial.k1_Nm_rad < 0.0) poly.FailField("k1_Nm_rad", "must not be negative");
  polynomial.k2_Nm_rad2 = poly.Number("k2_Nm_rad2", 0.0);
  polynomial.k3_Nm_rad3 = poly.Number("k3_Nm_rad3", 0.0);
  polynomial.c_Nms_rad = poly.NonNegative("c_Nms_rad", 0.0);
  if (support.Has("jenkins")) {
    ObjectReader j(support.Raw("jenkins"), top.source(), "support.jenkins", format_doc);
    jenkins = JenkinsSupportLaw::Parameters_{.stiffness_Nm_rad = j.Positive("stiffness_Nm_rad", 0.0),
                                             .slip_moment_Nm = j.Positive("slip_moment_Nm", 0.0)};
  }
  if (support.Has("one_sided")) {
    ObjectReader o(support.Raw("one_sided"), top.source(), "support.one_sided", format_doc);
    one_sided_stiffness_Nm_rad = o.Number("stiffness_Nm_rad");
    if (polynomial.k1_Nm_rad + one_sided_stiffness_Nm_rad < 0.0)
      o.FailField("stiffness_Nm_rad", "must not make k1 + stiffness_Nm_rad negative (a support that pushes)");
  }
}

// "attachments": {clamp_rotational_stiffness_Nm_rad, support_translational_stiffness_N_m,
//                 point_masses: [{position_m, mass_kg}]} (all optional).
inline void ReadAttachments(ObjectReader& top, const std::string& format_doc, LinearAttachments& attachments) {
  if (!top.Has("attachments")) return;
  ObjectReader a(top.Raw("attachments"), top.source(), "attachments", format_doc);
  if (a.Has("clamp_rotational_stiffness_Nm_rad"))
    attachments.clamp_rotational_stiffness_Nm_rad = a.Positive("clamp_rotational_stiffness_Nm_rad", 0.0);
  if (a.Has("support_translational_stiffness_N_m"))
    attachments.support_translational_stiffness_N_m = a.Positive("support_translational_stiffness_N_m", 0.0);
  if (a.Has("point_masses")) {
    const Json& masses = a.PointList("point_masses");
    for (size_t i = 0; i < masses.size(); ++i) {
      ObjectReader m(masses[i], top.source(), "attachments.point_masses[" + std::to_string(i) + "]", format_doc);
      attachments.point_masses.push_back({m.NonNegative("position_m", 0.0), m.Positive("mass_kg", 0.0)});
    }
  }
}

}  // namespace beamid::hb::internal
