// Coverage of the identification's 95 % intervals: the paper's
// set-up, base physics, three levels, simulated ONCE by the independent
// time-domain simulator (never by the harmonic-balance model being fitted);
// then independent realisations of the campaign's own measurement noise
// (hb/noise.h, as `beamid simulate` applies it) on those clean recordings,
// each extracted (signal/) and identified as `beamid identify` does.
// On physics the model holds (the simulator's own damping law, its steps
// settled: tests/support/coverage_study.h) the propagated intervals must be
// neither too wide nor too narrow for every parameter, the damping's
// included; every realisation must also reach the accuracy the tool
// promises (k1 within 1 %, c within 5 %, k3 within 10 %).
// Then the same with Rayleigh beam damping, fitted as such; and the model a
// diagnosis names for a recording fault (a sensor's gain off), whose fault
// and physics are fitted by turns and reported with the joint fit's
// uncertainties (the named friction's: diagnosis_friction_coverage_slow_test).
#include <string>

#include <gtest/gtest.h>

#include "solver/estimation/identify.h"
#include "tests/support/coverage_study.h"

namespace beamid::solver {
namespace {

using beamid::testing::ExpectCalibrated;
using beamid::testing::PrintStudy;

TEST(IdentificationCoverage, PropagatedIntervalsOfEveryParameterAreCalibratedOnThePhysicsTheModelHolds) {
  // The paper's example with the simulator's own damping law (the modal loss
  // factor), its steps settled; fitted as `beamid identify` does.
  const beamid::testing::CoveragePhysics physics =
      beamid::testing::MakeCoveragePhysics("modal_loss_factor", beamid::testing::CoverageSettling::kTight);
  ASSERT_EQ(physics.scenario.NumSteps(), 45);
  const std::vector<double>& truth = physics.truth;  // k1, k2, k3, c, η_m
  const beamid::testing::CoverageStudy study = beamid::testing::RunCoverageStudy(
      physics, {.uncertainty = PhasorUncertainty::kPropagated}, 50, 1000, [&](int r, const IdentifyResult& result) {
        // The accuracy promised, on every realisation (k2's "within its
        // interval" is a 95 % statement: the coverage below checks it).
        EXPECT_NEAR(result.parameters[0].value, truth[0], 0.01 * truth[0]) << "realisation " << r;
        EXPECT_NEAR(result.parameters[2].value, truth[2], 0.10 * truth[2]) << "realisation " << r;
        EXPECT_NEAR(result.parameters[3].value, truth[3], 0.05 * truth[3]) << "realisation " << r;
      });
  PrintStudy(study);
  ASSERT_EQ(study.parameters.size(), 5u);
  for (std::size_t j = 0; j < study.parameters.size(); ++j) ExpectCalibrated(study, j);
}

TEST(IdentificationCoverage, PropagatedIntervalsOfEveryParameterAreCalibratedWithRayleighDamping) {
  // Another damping law the model holds exactly: Rayleigh's α, β beside c.
  const beamid::testing::CoveragePhysics physics =
      beamid::testing::MakeCoveragePhysics("rayleigh", beamid::testing::CoverageSettling::kTight);
  const beamid::testing::CoverageStudy study =
      beamid::testing::RunCoverageStudy(physics, {.uncertainty = PhasorUncertainty::kPropagated}, 50, 1000);
  PrintStudy(study);
  ASSERT_EQ(study.parameters.size(), 6u);
  for (std::size_t j = 0; j < study.parameters.size(); ++j) ExpectCalibrated(study, j);
}

TEST(DiagnosisCoverage, TheNamedRecordingFaultsIntervalsHoldOnThePhysicsTheModelHolds) {
  // acc2 reads 1 % high, 20 times the smallest gain error named 9 times in
  // 10; beside it the diagnosed model holds the simulated physics exactly
  // (steps settled, the beam's damping fitted as the simulator's law).
  // 100 realisations: the gain's rms z has a sampling σ of about 0.07, so a
  // calibrated interval reads below 0.8 with probability 0.002; 50 did not
  // suffice (the first 50 seeds read 0.77, the next 50 1.13).
  const beamid::testing::ConcealedCause cause =
      beamid::testing::MakeConcealedCause("sensor_gain", beamid::testing::ConcealedPhysics::kExact);
  const beamid::testing::DiagnosisCoverageStudy study =
      beamid::testing::RunDiagnosisCoverageStudy(cause, {.realisations = 100});
  PrintStudy(study.coverage);
  // A realisation may name a pair (a false alarm beside the fault): at most one in 25.
  EXPECT_GE(study.named, 96);
  ASSERT_EQ(study.coverage.parameters.size(), 6u);  // k1, k2, k3, c, η_m, the gain error
  for (std::size_t j = 0; j < study.coverage.parameters.size(); ++j) ExpectCalibrated(study.coverage, j);
}

}  // namespace
}  // namespace beamid::solver
