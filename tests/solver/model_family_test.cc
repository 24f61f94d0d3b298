// The model-family interface against each family's own fit problem: the
// model that predict and report rebuild from a result (the family's
// DisplacementAt, solved again from the fitted states) must give the
// phasors the fit problem had at its solution, at the fitted channels and
// at a position the fit never saw — for every family, so that a new family
// that names its state wrongly or rebuilds another branch fails here.
#include "solver/estimation/model_family.h"

#include <cmath>
#include <set>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "hb/errors.h"
#include "solver/estimation/fit_problem.h"
#include "solver/estimation/prediction.h"
#include "solver/estimation/sensor_backbone.h"
#include "tests/support/expect_refused.h"
#include "tests/support/synthetic_fit_data.h"

namespace beamid::solver {
namespace {

using ::testing::HasSubstr;

ModelStructure Structure() {
  ModelStructure structure = PolynomialModel({});
  structure.linear.push_back(LossFactor());
  return structure;
}
const std::vector<double> kParameters = {150.0, 800.0, 3e5, 0.05, 2e-4};

// The identified model as a result file would give it: nominal beam,
// fitted values, each step's state from the problem.
IdentifiedModel Rebuilt(const ModelFamily& family, const FitData& data, FitProblem& problem, const Eigen::VectorXd& x) {
  IdentifiedModel model;
  model.family = &family;
  model.beam.beam = data.beam;
  model.force_position_m = data.force_position_m;
  model.num_harmonics = problem.num_model_harmonics();
  model.structure = Structure();
  model.structure.SetValues(kParameters);
  for (int i = 0; i < problem.num_steps(); ++i) {
    const FitStep& s = data.steps[i];
    model.steps.push_back(
        {.level = s.level, .file = s.file, .omega_rad_s = s.omega_rad_s, .force_N = s.force_N, .state = problem.StepState(x, i)});
  }
  return model;
}

TEST(ModelFamily, RebuildsFromItsStatesThePhasorsOfItsFitProblem) {
  const FitData data = testing::SyntheticFitData();
  for (const ModelFamily* family : ModelFamilies()) {
    SCOPED_TRACE(family->Name());
    const ModelOptions options{.num_harmonics = 5};
    EXPECT_NO_THROW(family->CheckCanHold(data, Structure(), options));
    const std::unique_ptr<FitProblem> problem = family->MakeProblem(data, Structure(), options);
    int failed = -1;
    const Eigen::VectorXd x = problem->FeasiblePoint(kParameters, &failed);
    ASSERT_EQ(failed, 0);
    const int h = problem->num_model_harmonics();
    EXPECT_EQ(h, family->ModelHarmonics(options.num_harmonics));
    for (int i = 0; i < problem->num_steps(); ++i)
      EXPECT_EQ(problem->StepState(x, i).size(), family->StateSize(h));

    const IdentifiedModel model = Rebuilt(*family, data, *problem, x);
    for (double position_m : {0.1, 0.3, 0.45}) {  // the fitted channels, and one unseen
      std::vector<bool> converged(model.steps.size(), false);
      const std::vector<Eigen::VectorXcd> rebuilt = family->DisplacementAt(model, kParameters, position_m, &converged);
      ASSERT_EQ(rebuilt.size(), data.steps.size());
      for (int i = 0; i < problem->num_steps(); ++i) {
        SCOPED_TRACE("x = " + std::to_string(position_m) + " m, step " + std::to_string(i));
        EXPECT_TRUE(converged[i]);
        const Eigen::VectorXcd fitted = problem->DisplacementPhasors(x, i, {position_m}).row(0).transpose();
        ASSERT_GE(rebuilt[i].size(), 4);
        ASSERT_GE(fitted.size(), 4);
        // Harmonics 1..3, each to 1e-8 of the fundamental (the solvers'
        // tolerance; a wrong branch or state is off by O(1)).
        for (int k = 1; k <= 3; ++k)
          EXPECT_LT(std::abs(rebuilt[i][k] - fitted[k]), 1e-8 * std::abs(fitted[1])) << "harmonic " << k;
      }
    }
  }
}

TEST(ModelFamily, FittedDisplacementsAreThePhasorsOfItsFitProblemAsTheyStand) {
  // The residual map's phasors: from the states as fitted (off the
  // balance too), not solved again.
  const FitData data = testing::SyntheticFitData();
  const std::vector<double> positions_m = {0.1, 0.3, 0.45};
  for (const ModelFamily* family : ModelFamilies()) {
    SCOPED_TRACE(family->Name());
    const std::unique_ptr<FitProblem> problem = family->MakeProblem(data, Structure(), {.num_harmonics = 5});
    Eigen::VectorXd x = problem->FeasiblePoint(kParameters);
    for (int i = problem->num_parameters(); i < x.size(); ++i) x[i] *= 1.0 + 0.03 * (i % 3);
    const std::vector<Eigen::MatrixXcd> fitted = family->FittedDisplacements(Rebuilt(*family, data, *problem, x), positions_m);
    ASSERT_EQ(fitted.size(), data.steps.size());
    for (int i = 0; i < problem->num_steps(); ++i) {
      const Eigen::MatrixXcd expected = problem->DisplacementPhasors(x, i, positions_m);
      ASSERT_EQ(fitted[i].rows(), expected.rows());
      ASSERT_EQ(fitted[i].cols(), expected.cols());
      EXPECT_LT((fitted[i] - expected).cwiseAbs().maxCoeff(), 1e-9 * expected.cwiseAbs().maxCoeff()) << "step " << i;
    }
  }
}

TEST(ModelFamily, BackbonesAtASensorAgreeBetweenFamilies) {
  // Two independent models of one beam and support: at equal amplitude of
  // the sensor their backbones agree to 0.1 % at these small amplitudes.
  const FitData data = testing::SyntheticFitData();
  std::vector<std::vector<SensorBackbonePoint>> backbones;
  for (const ModelFamily* family : ModelFamilies()) {
    SCOPED_TRACE(family->Name());
    const std::unique_ptr<FitProblem> problem = family->MakeProblem(data, Structure(), {.num_harmonics = 5});
    const IdentifiedModel model = Rebuilt(*family, data, *problem, problem->FeasiblePoint(kParameters));
    backbones.push_back(family->BackboneAtSensor(model, 0.3, 20));
    ASSERT_GE(backbones.back().size(), 10u);
    for (std::size_t n = 1; n < backbones.back().size(); ++n)
      EXPECT_GT(backbones.back()[n].amplitude_m, backbones.back()[n - 1].amplitude_m);
  }
  int compared = 0;
  for (const SensorBackbonePoint& p : backbones[1]) {
    const double f = BackboneFrequencyAt_hz(backbones[0], p.amplitude_m);
    if (!std::isfinite(f)) continue;
    EXPECT_NEAR(p.frequency_hz, f, 1e-3 * f) << "|Y_1| = " << p.amplitude_m;
    ++compared;
  }
  EXPECT_GE(compared, 5);
}

TEST(ModelFamily, OnlyHarmonicBalanceStatesAreTheSupportRotation) {
  const Eigen::VectorXcd state = Eigen::VectorXcd::Constant(6, std::complex<double>(1e-3, 2e-4));
  EXPECT_EQ(HarmonicBalanceFamily().SupportRotation_rad(state), state);
  EXPECT_EQ(MultipleScalesFamily().SupportRotation_rad(Eigen::VectorXcd::Constant(1, 1e-4)).size(), 0);
}

TEST(ModelFamily, NamesAreUniqueAndFindable) {
  std::set<std::string> names, state_names;
  for (const ModelFamily* family : ModelFamilies()) {
    EXPECT_TRUE(names.insert(family->Name()).second) << family->Name();
    EXPECT_EQ(&FindModelFamily(family->Name()), family);
    EXPECT_FALSE(family->Description().empty());
  }
  EXPECT_EQ(FindModelFamily("hb").StateName(), "theta_rad");
  EXPECT_EQ(FindModelFamily("ms").StateName(), "modal_phasor_m");
  const std::string message = testing::InputErrorOf([] { FindModelFamily("fe"); });
  EXPECT_THAT(message, HasSubstr("model 'fe'"));
  EXPECT_THAT(message, HasSubstr("hb (harmonic balance)"));
  EXPECT_THAT(message, HasSubstr("ms (multiple scales)"));
}

TEST(ModelFamily, MultipleScalesRefusesWhatItCannotHoldBeforeAnyWork) {
  FitData with_masses = testing::SyntheticFitData();
  with_masses.sensor_masses.point_masses = {{.position_m = 0.1, .mass_kg = 0.005}};
  EXPECT_THROW(MultipleScalesFamily().CheckCanHold(with_masses, Structure(), {}), std::invalid_argument);
  EXPECT_NO_THROW(HarmonicBalanceFamily().CheckCanHold(with_masses, Structure(), {}));
}

}  // namespace
}  // namespace beamid::solver
