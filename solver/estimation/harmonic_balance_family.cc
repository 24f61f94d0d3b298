// The exact harmonic-balance family: IdentificationProblem to fit, and for
// prediction the harmonic balance of the identified model solved at every
// step from its fitted rotation Θ (the branch the test was on).
#include "hb/harmonic_balance.h"
#include "solver/estimation/identification_problem.h"
#include "solver/estimation/model_family.h"
#include "solver/estimation/prediction.h"

namespace beamid::solver {
namespace {

class HarmonicBalanceFamilyImpl final : public ModelFamily {
 public:
  ModelKind Kind() const override { return ModelKind::kHarmonicBalance; }
  std::string Description() const override { return "harmonic balance"; }
  std::string StateName() const override { return "theta_rad"; }
  int StateSize(int num_harmonics) const override { return num_harmonics + 1; }
  int ModelHarmonics(int requested_harmonics) const override { return requested_harmonics; }

  void CheckCanHold(const FitData&, const ModelStructure&, const ModelOptions& options) const override {
    options.Validate();
  }
  std::unique_ptr<FitProblem> MakeProblem(const FitData& data, const ModelStructure& structure,
                                          const ModelOptions& options) const override {
    return std::make_unique<IdentificationProblem>(data, structure, options);
  }

  std::vector<Eigen::VectorXcd> DisplacementAt(const IdentifiedModel& model, const std::vector<double>& p,
                                               double position_m, std::vector<bool>* converged) const override {
    const hb::HarmonicBalance balance = IdentifiedHarmonicBalance(model, p);
    std::vector<Eigen::VectorXcd> out;
    for (std::size_t i = 0; i < model.steps.size(); ++i) {
      const IdentifiedStep& s = model.steps[i];
      const auto solution = balance.Solve(s.omega_rad_s, s.force_N,
                                          hb::HarmonicBalance::ToReal(hb::PadHarmonics(s.state, model.num_harmonics)));
      if (converged) (*converged)[i] = solution.converged;
      out.push_back(balance.Displacements(solution, s.force_N, {position_m}).row(0).transpose());
    }
    return out;
  }

  Eigen::VectorXcd SupportRotation_rad(const Eigen::VectorXcd& state) const override { return state; }
};

}  // namespace

const ModelFamily& HarmonicBalanceFamily() {
  static const HarmonicBalanceFamilyImpl family;
  return family;
}

}  // namespace beamid::solver
