#include "solver/diagnosis/fitted_model.h"

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

}  // namespace beamid::solver
