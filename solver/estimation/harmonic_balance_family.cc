// The exact harmonic-balance family: IdentificationProblem to fit, and for
// prediction the harmonic balance of the identified model solved at every
// step from its fitted rotation Θ (the branch the test was on).
#include <algorithm>
#include <cmath>

#include "hb/continuation.h"
#include "hb/harmonic_balance.h"
#include "solver/estimation/identification_problem.h"
#include "solver/estimation/model_family.h"
#include "solver/estimation/prediction.h"
#include "solver/estimation/sensor_backbone.h"

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

  std::vector<Eigen::MatrixXcd> FittedDisplacements(const IdentifiedModel& model,
                                                    const std::vector<double>& positions_m) const override {
    const hb::HarmonicBalance balance = IdentifiedHarmonicBalance(model);
    std::vector<Eigen::MatrixXcd> out;
    for (const IdentifiedStep& s : model.steps) {
      const hb::HarmonicBalanceSolution solution{.omega_rad_s = s.omega_rad_s,
                                                 .theta_rad = hb::PadHarmonics(s.state, model.num_harmonics)};
      out.push_back(balance.Displacements(solution, s.force_N, positions_m));
    }
    return out;
  }

  // Pseudo-arclength continuation of the harmonic balance (hb/continuation.h).
  ModelResponse FrequencyResponse(const IdentifiedModel& model, double force_amplitude_N, double omega_start_rad_s,
                                  double omega_end_rad_s, int max_points, const std::vector<double>& positions_m,
                                  const std::function<void(double)>& on_fraction) const override {
    const hb::HarmonicBalance balance = IdentifiedHarmonicBalance(model);
    Eigen::VectorXcd force = Eigen::VectorXcd::Zero(2);
    force[1] = force_amplitude_N;
    const auto summary = hb::TraceFrequencyResponse(
        balance, force,
        {.omega_start_rad_s = omega_start_rad_s, .omega_end_rad_s = omega_end_rad_s, .max_points = max_points},
        on_fraction);
    ModelResponse response{.reached_end = summary.reached_end, .message = summary.message};
    for (const auto& p : summary.points) {
      const hb::HarmonicBalanceSolution solution{.omega_rad_s = p.omega_rad_s, .theta_rad = p.theta_rad};
      response.points.push_back({.omega_rad_s = p.omega_rad_s,
                                 .stable = p.stable,
                                 .displacement_m = balance.Displacements(solution, force, positions_m)});
    }
    return response;
  }

  // The sensor's phase resonance along the backbone of θ, over the steps' |Θ_1|.
  std::vector<SensorBackbonePoint> BackboneAtSensor(const IdentifiedModel& model, double sensor_position_m,
                                                    int num_points) const override {
    const double theta_max = LargestStateAmplitude(model, 1);
    if (theta_max <= 0.0) return {};
    return ModelBackboneAtSensor(model.structure.ApplyLinear(model.beam), *model.structure.law, model.force_position_m,
                                 sensor_position_m,
                                 {.min_theta_amplitude_rad = theta_max / 30.0,
                                  .max_theta_amplitude_rad = 1.3 * theta_max,
                                  .num_points = num_points},
                                 model.num_harmonics);
  }

  Eigen::VectorXcd SupportRotation_rad(const Eigen::VectorXcd& state) const override { return state; }
};

}  // namespace

const ModelFamily& HarmonicBalanceFamily() {
  static const HarmonicBalanceFamilyImpl family;
  return family;
}

}  // namespace beamid::solver
