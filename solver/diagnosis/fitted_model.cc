#include "solver/diagnosis/fitted_model.h"

#include <cmath>

#include "solver/estimation/model_phasors.h"

namespace beamid::solver {

FittedModel::FittedModel(const FitData& fit, const ModelFamily& model_family, const ModelStructure& s, int harmonics,
                         const std::vector<double>& scaled_at, Eigen::VectorXd variables,
                         const std::vector<double>& values)
    : data(fit), family(&model_family), structure(s), x(std::move(variables)), model_harmonics(harmonics) {
  problem = model_family.MakeProblem(fit, structure, ModelOptions{.num_harmonics = harmonics});
  problem->FeasiblePoint(scaled_at);
  // After the problem: its internal scales are those of the structure the
  // optimiser started from.
  structure.SetValues(values);
}

std::vector<Eigen::MatrixXcd> FittedModel::Phasors(const FitData& at) const { return ModelPhasors(at, *problem, x); }

IdentifiedModel FittedModel::Identified() const {
  IdentifiedModel model{.family = family,
                        .beam = {.beam = data.beam, .attachments = data.sensor_masses},
                        .force_position_m = data.force_position_m,
                        .num_harmonics = model_harmonics,
                        .structure = structure};
  for (int i = 0; i < static_cast<int>(data.steps.size()); ++i) {
    const FitStep& s = data.steps[static_cast<std::size_t>(i)];
    model.steps.push_back({.level = s.level,
                           .file = s.file,
                           .omega_rad_s = s.omega_rad_s,
                           .force_N = s.force_N,
                           .state = problem->StepState(x, i)});
  }
  return model;
}

std::vector<double> FittedModel::SupportRotationAmplitudes_rad() const {
  std::vector<double> amplitudes;
  for (int i = 0; i < problem->num_steps(); ++i) {
    const Eigen::VectorXcd theta = family->SupportRotation_rad(problem->StepState(x, i));
    if (theta.size() < 2) return SupportRotationAmplitudesFromShape_rad();
    amplitudes.push_back(std::abs(theta[1]));
  }
  return amplitudes;
}

std::vector<double> FittedModel::SupportRotationAmplitudesFromShape_rad() const {
  // δ small against the first mode's wavelength (the difference's error is
  // O(δ²) in the shape's third derivative) and large against the rounding
  // of y (O(ε|y|/δ)).
  const double length_m = data.beam.length_m, delta_m = 1e-3 * length_m;
  const std::vector<Eigen::MatrixXcd> y =
      family->FittedDisplacements(Identified(), {length_m, length_m - delta_m, length_m - 2.0 * delta_m});
  std::vector<double> amplitudes;
  for (const Eigen::MatrixXcd& step : y)
    amplitudes.push_back(std::abs((3.0 * step(0, 1) - 4.0 * step(1, 1) + step(2, 1)) / (2.0 * delta_m)));
  return amplitudes;
}

}  // namespace beamid::solver
