// What is identified: a support law whose parameters are unknown (with their
// bounds and typical sizes) and, optionally, linear parameters of the beam
// (a scale of the nominal bending stiffness EI, clamp compliance, an added
// mass, …), each of which edits the linear beam model.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "hb/linear_beam.h"
#include "hb/support_law.h"

namespace beamid::solver {

struct ParameterBounds {
  double lower = -1e30;
  double upper = 1e30;
  double typical = 1.0;  // scale of the optimiser's variable: value / typical ~ 1
};

struct LinearParameter {
  std::string name;
  std::string unit;
  double initial = 0.0;
  ParameterBounds bounds;
  // Writes the value into the linear model (e.g. EI scale: multiplies E).
  std::function<void(hb::LinearBeamModel&, double)> apply;
};

struct ModelStructure {
  std::unique_ptr<hb::SupportLaw> law;     // its current values are the initial guess
  std::vector<ParameterBounds> law_bounds; // one per law parameter
  std::vector<LinearParameter> linear;

  ModelStructure() = default;
  ModelStructure(const ModelStructure& other);
  ModelStructure& operator=(const ModelStructure& other);
  ModelStructure(ModelStructure&&) = default;
  ModelStructure& operator=(ModelStructure&&) = default;

  int NumParameters() const { return static_cast<int>(law_bounds.size() + linear.size()); }
  // Names, units and current values: the law's, then the linear ones.
  std::vector<std::string> Names() const;
  std::vector<std::string> Units() const;
  std::vector<double> Values() const;
  std::vector<ParameterBounds> Bounds() const;
  // Sets all values (law, then linear) — throws on a size mismatch.
  void SetValues(const std::vector<double>& values);
  // The linear beam model with the linear parameters applied to `base`.
  hb::LinearBeamModel ApplyLinear(const hb::LinearBeamModel& base) const;
};

// The paper's law M = k1·θ + k2·θ² + k3·θ³ + c·θ̇ with physical bounds
// (k1 ≥ 0, c ≥ 0) and typical sizes for a beam of this kind.
ModelStructure PolynomialModel(const hb::PolynomialSupportLaw::Coefficients& initial);

// A multiplier of the nominal bending stiffness EI (the modulus or the
// thickness of the real beam differ from the nominal ones by a few per cent).
LinearParameter BendingStiffnessScale();

// The beam's structural loss factor η (material damping, E(1 + iη)): light,
// unknown in a real test, and entangled with the support's c; fitting it
// keeps c from absorbing the beam's own damping.
LinearParameter LossFactor(double initial = 1e-3);

// The beam's loss factor matched per mode at its driving harmonic, η_m
// (hb/matched_modal_loss.h): the damping of time-domain codes and of a
// constant modal damping ratio, which the loss factor cannot represent.
LinearParameter ModalLossFactor(double initial = 1e-3);

// The beam's Rayleigh damping C = α·M + β·K (hb/beam_properties.h): α [1/s]
// and β [s], the damping laws a loss factor cannot represent (mode j's ratio
// α/(2ω_j) + β·ω_j/2 against η/2 for every mode).
LinearParameter RayleighMassDamping(double initial = 0.0);
LinearParameter RayleighStiffnessDamping(double initial = 0.0);

// The linear parameter of that name ("EI_scale", "loss_factor", "modal_loss_factor",
// "rayleigh_…"), to rebuild
// a fitted model from a result file; throws std::invalid_argument otherwise.
LinearParameter LinearParameterByName(const std::string& name, double value);

}  // namespace beamid::solver
