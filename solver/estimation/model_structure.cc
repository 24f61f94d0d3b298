#include "solver/estimation/model_structure.h"

#include <algorithm>
#include <stdexcept>

namespace beamid::solver {

ModelStructure::ModelStructure(const ModelStructure& other)
    : law(other.law ? other.law->Clone() : nullptr), law_bounds(other.law_bounds), linear(other.linear) {}

ModelStructure& ModelStructure::operator=(const ModelStructure& other) {
  if (this != &other) {
    law = other.law ? other.law->Clone() : nullptr;
    law_bounds = other.law_bounds;
    linear = other.linear;
  }
  return *this;
}

std::vector<std::string> ModelStructure::Names() const {
  std::vector<std::string> names;
  for (const auto& p : law->Parameters()) names.push_back(p.name);
  for (const auto& p : linear) names.push_back(p.name);
  return names;
}

std::vector<std::string> ModelStructure::Units() const {
  std::vector<std::string> units;
  for (const auto& p : law->Parameters()) units.push_back(p.unit);
  for (const auto& p : linear) units.push_back(p.unit);
  return units;
}

std::vector<double> ModelStructure::Values() const {
  std::vector<double> values;
  for (const auto& p : law->Parameters()) values.push_back(p.value);
  for (const auto& p : linear) values.push_back(p.initial);
  return values;
}

std::vector<ParameterBounds> ModelStructure::Bounds() const {
  std::vector<ParameterBounds> bounds = law_bounds;
  for (const auto& p : linear) bounds.push_back(p.bounds);
  return bounds;
}

void ModelStructure::SetValues(const std::vector<double>& values) {
  if (static_cast<int>(values.size()) != NumParameters())
    throw std::invalid_argument("ModelStructure::SetValues: wrong number of values");
  const std::size_t num_law = law_bounds.size();
  law->SetParameterValues(std::span<const double>(values.data(), num_law));
  for (std::size_t j = 0; j < linear.size(); ++j) linear[j].initial = values[num_law + j];
}

hb::LinearBeamModel ModelStructure::ApplyLinear(const hb::LinearBeamModel& base) const {
  hb::LinearBeamModel model = base;
  for (const auto& p : linear) p.apply(model, p.initial);
  return model;
}

ModelStructure PolynomialModel(const hb::PolynomialSupportLaw::Coefficients& initial) {
  ModelStructure structure;
  structure.law = std::make_unique<hb::PolynomialSupportLaw>(initial);
  structure.law_bounds = {
      {.lower = 0.0, .upper = 1e6, .typical = 100.0},     // k1 [N·m/rad]
      {.lower = -1e9, .upper = 1e9, .typical = 1e3},      // k2 [N·m/rad²]
      {.lower = -1e12, .upper = 1e12, .typical = 1e5},    // k3 [N·m/rad³]
      {.lower = 0.0, .upper = 1e3, .typical = 0.01},      // c [N·m·s/rad]
  };
  return structure;
}

LinearParameter BendingStiffnessScale() {
  return {.name = "EI_scale",
          .unit = "1",
          .initial = 1.0,
          .bounds = {.lower = 0.5, .upper = 1.5, .typical = 1.0},
          .apply = [](hb::LinearBeamModel& model, double scale) { model.beam.youngs_modulus_Pa *= scale; }};
}

LinearParameter LossFactor(double initial) {
  return {.name = "loss_factor",
          .unit = "1",
          .initial = initial,
          .bounds = {.lower = 0.0, .upper = 0.05, .typical = 1e-3},
          // Ipopt relaxes bounds by ~1e-8: a fit that wants no beam damping may
          // step a hair below 0, which the beam rejects.
          .apply = [](hb::LinearBeamModel& model, double eta) { model.beam.loss_factor = std::max(eta, 0.0); }};
}

LinearParameter ModalLossFactor(double initial) {
  return {.name = "modal_loss_factor",
          .unit = "1",
          .initial = initial,
          .bounds = {.lower = 0.0, .upper = 0.05, .typical = 1e-3},
          .apply = [](hb::LinearBeamModel& model, double eta) { model.beam.modal_loss_factor = std::max(eta, 0.0); }};
}

LinearParameter RayleighMassDamping(double initial) {
  return {.name = "rayleigh_mass_1_s",
          .unit = "1/s",
          .initial = initial,
          .bounds = {.lower = 0.0, .upper = 100.0, .typical = 0.1},
          .apply = [](hb::LinearBeamModel& model, double alpha) { model.beam.rayleigh_mass_1_s = std::max(alpha, 0.0); }};
}

LinearParameter RayleighStiffnessDamping(double initial) {
  return {.name = "rayleigh_stiffness_s",
          .unit = "s",
          .initial = initial,
          .bounds = {.lower = 0.0, .upper = 1e-3, .typical = 1e-6},
          .apply = [](hb::LinearBeamModel& model, double beta) { model.beam.rayleigh_stiffness_s = std::max(beta, 0.0); }};
}

LinearParameter LinearParameterByName(const std::string& name, double value) {
  for (LinearParameter p :
       {BendingStiffnessScale(), LossFactor(), ModalLossFactor(), RayleighMassDamping(), RayleighStiffnessDamping()})
    if (p.name == name) {
      p.initial = value;
      return p;
    }
  throw std::invalid_argument("unknown linear parameter '" + name + "' (known: EI_scale, loss_factor, modal_loss_factor, rayleigh_mass_1_s, rayleigh_stiffness_s)");
}

}  // namespace beamid::solver
