// Coverage of the intervals of the friction model a diagnosis names: the
// paper set-up (3 levels × 9 steps) with a Jenkins element beside the
// support's spring (50 N·m/rad slipping at 0.15 N·m, beside k1 = 100),
// simulated by the independent time-domain simulator with every step
// settled to 1e-8, diagnosed with the simulator's own damping law, so that
// once the friction is named the model holds the simulated physics. The
// slipping steps never settle (tests/support/coverage_study.h,
// CoverageRecords), so each of the 50 realisations is simulated anew, its
// settling cut 0.37 s later than the last's, before its noise is drawn.
// The friction is the only candidate (CoverageCandidates): the named
// model's intervals are those of the whole diagnosis, which names it in 50
// of 50 as well (coverage_benchmark, friction_exact_resimulated_propagated).
// Each realisation simulates only the levels that hold a slipping step, up
// to the last one (UpToTheUnsettledSteps). 24 min beside the rest of the
// suite on 2 cores (1439 s; 1752 s before the simulator's step and the
// harmonic balance's sparse derivatives): it runs past ctest's default
// timeout (tests/CMakeLists.txt).
#include <gtest/gtest.h>

#include "tests/support/coverage_study.h"

namespace beamid::solver {
namespace {

using beamid::testing::ExpectCalibrated;
using beamid::testing::PrintStudy;

TEST(DiagnosisCoverage, TheNamedFrictionModelsIntervalsHoldOnThePhysicsTheModelHolds) {
  const beamid::testing::ConcealedCause cause =
      beamid::testing::MakeConcealedCause("friction", beamid::testing::ConcealedPhysics::kExact);
  const beamid::testing::DiagnosisCoverageStudy study = beamid::testing::RunDiagnosisCoverageStudy(
      cause, {.records = beamid::testing::CoverageRecords::kSimulatedPerRealisation,
              .candidates = beamid::testing::CoverageCandidates::kTheCauseAlone});
  PrintStudy(study.coverage);
  EXPECT_EQ(study.named, 50);
  ASSERT_EQ(study.coverage.parameters.size(), 7u);  // k1, k2, k3, c, η_m, k_t, M_slip
  for (std::size_t j = 0; j < study.coverage.parameters.size(); ++j) ExpectCalibrated(study.coverage, j);
}

}  // namespace
}  // namespace beamid::solver
