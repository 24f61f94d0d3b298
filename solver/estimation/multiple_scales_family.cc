// The seed's multiple-scales family: MultipleScalesProblem to fit, and for
// prediction the root of the amplitude equation nearest the fitted modal
// phasor U (the branch the test was on), harmonics 0..3 from the force's
// fundamental.
#include <algorithm>
#include <complex>
#include <stdexcept>

#include "hb/multiple_scales.h"
#include "solver/estimation/model_family.h"
#include "solver/estimation/multiple_scales_problem.h"
#include "solver/estimation/prediction.h"

namespace beamid::solver {
namespace {

using Complex = std::complex<double>;

MultipleScalesProblemOptions ProblemOptions(const ModelOptions& options) {
  return {.beam_loss_factor = options.beam_loss_factor};
}

class MultipleScalesFamilyImpl final : public ModelFamily {
 public:
  ModelKind Kind() const override { return ModelKind::kMultipleScales; }
  std::string Description() const override { return "multiple scales"; }
  std::string StateName() const override { return "modal_phasor_m"; }
  int StateSize(int) const override { return 1; }
  int ModelHarmonics(int) const override { return 3; }

  // The problem's constructor refuses sensor masses, more than 3 fitted
  // harmonics and another law.
  void CheckCanHold(const FitData& data, const ModelStructure& structure, const ModelOptions& options) const override {
    options.Validate();
    const MultipleScalesProblem check(data, structure, ProblemOptions(options));
  }
  std::unique_ptr<FitProblem> MakeProblem(const FitData& data, const ModelStructure& structure,
                                          const ModelOptions& options) const override {
    return std::make_unique<MultipleScalesProblem>(data, structure, ProblemOptions(options));
  }

  std::vector<Eigen::VectorXcd> DisplacementAt(const IdentifiedModel& model, const std::vector<double>& p,
                                               double position_m, std::vector<bool>* converged) const override {
    const hb::MultipleScalesModel ms =
        MakeMultipleScalesModel(model.beam.beam, model.force_position_m, model.structure, p);
    std::vector<Eigen::VectorXcd> out;
    for (std::size_t i = 0; i < model.steps.size(); ++i) {
      const IdentifiedStep& s = model.steps[i];
      Eigen::VectorXcd y = Eigen::VectorXcd::Zero(4);
      bool solved = false;
      try {
        const std::vector<Complex> roots = ms.Solve(s.omega_rad_s, s.force_N[1]);
        const Complex fitted = s.state[0];
        const Complex u = *std::min_element(roots.begin(), roots.end(), [&](Complex a, Complex b) {
          return std::abs(a - fitted) < std::abs(b - fitted);
        });
        const hb::MultipleScalesModel::Harmonics h = ms.Response(position_m, u, s.omega_rad_s, s.force_N[1]);
        y << h.h0_m, h.h1_m, h.h2_m, h.h3_m;
        solved = true;
      } catch (const std::runtime_error&) {
        // An internal resonance at 2Ω or 3Ω: the model has no steady state here.
      }
      if (converged) (*converged)[i] = solved;
      out.push_back(y);
    }
    return out;
  }

  // U is the first mode's amplitude, not the rotation's harmonics.
  Eigen::VectorXcd SupportRotation_rad(const Eigen::VectorXcd&) const override { return {}; }
};

}  // namespace

const ModelFamily& MultipleScalesFamily() {
  static const MultipleScalesFamilyImpl family;
  return family;
}

}  // namespace beamid::solver
