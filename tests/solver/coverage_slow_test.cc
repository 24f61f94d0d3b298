// Coverage of the identification's 95 % intervals: the paper's
// set-up, base physics, three levels, simulated ONCE by the independent
// time-domain simulator (never by the harmonic-balance model being fitted);
// then independent realisations of the campaign's own measurement noise
// (hb/noise.h, as `beamid simulate` applies it) on those clean recordings,
// each extracted (signal/) and identified as `beamid identify` does (k1, k2,
// k3, c and the beam's loss factor η). For every parameter the truth must
// lie in the reported 95 % interval in 85–100 % of the realisations, and
// every realisation must meet the first check of the issue (k1 within 1 %,
// c within 5 %, k3 within 10 %, k2 within its interval).
// Then the propagated weighting on physics the model holds exactly (Rayleigh
// beam damping, fitted as such; tests/support/coverage_study.h), where the
// intervals must be neither too wide nor too narrow.
#include <cstdio>
#include <string>

#include <gtest/gtest.h>

#include "solver/estimation/identify.h"
#include "tests/support/coverage_study.h"

namespace beamid::solver {
namespace {

void PrintStudy(const beamid::testing::CoverageStudy& study) {
  for (std::size_t j = 0; j < study.parameters.size(); ++j)
    std::printf("%-22s coverage %5.1f %%, mean z %+.2f, rms z %.2f\n", study.parameters[j].name.c_str(),
                100.0 * study.Coverage(j), study.MeanZ(j), study.RmsZ(j));
}

TEST(IdentificationCoverage, TruthLiesInThe95PercentIntervalsIn85To100PercentOfNoiseRealisations) {
  // The paper's example with its loss factor, fitted as `beamid identify` does.
  const beamid::testing::CoveragePhysics physics = beamid::testing::MakeCoveragePhysics("loss_factor");
  ASSERT_EQ(physics.scenario.NumSteps(), 45);
  const std::vector<double>& truth = physics.truth;  // k1, k2, k3, c, η
  const beamid::testing::CoverageStudy study =
      beamid::testing::RunCoverageStudy(physics, {}, 30, 1000, [&](int r, const IdentifyResult& result) {
        // The first check, on every realisation.
        EXPECT_NEAR(result.parameters[0].value, truth[0], 0.01 * truth[0]) << "realisation " << r;
        EXPECT_NEAR(result.parameters[2].value, truth[2], 0.10 * truth[2]) << "realisation " << r;
        EXPECT_NEAR(result.parameters[3].value, truth[3], 0.05 * truth[3]) << "realisation " << r;
        EXPECT_LE(result.parameters[1].lower_95, truth[1]) << "k2, realisation " << r;
        EXPECT_GE(result.parameters[1].upper_95, truth[1]) << "k2, realisation " << r;
      });
  PrintStudy(study);
  // One-sided: under the default relative floor the intervals are too wide
  // (the second test and docs/identify.md, "Coverage, measured").
  for (std::size_t j = 0; j < study.parameters.size(); ++j)
    EXPECT_GE(study.Coverage(j), 0.85) << study.parameters[j].name << ": mean z " << study.MeanZ(j);
}

// 50 realisations: rms z has a sampling σ of about 1/√100 = 0.1.
TEST(IdentificationCoverage, PropagatedIntervalsOfTheStiffnessesAreNeitherTooWideNorTooNarrowOnExactPhysics) {
  const beamid::testing::CoveragePhysics physics = beamid::testing::MakeCoveragePhysics("rayleigh");
  const beamid::testing::CoverageStudy study =
      beamid::testing::RunCoverageStudy(physics, {.uncertainty = PhasorUncertainty::kPropagated}, 50, 1000);
  PrintStudy(study);
  // k1, k2, k3. The damping parameters (c, α, β) read rms z ~1.3, mostly a
  // fixed offset of the simulation from the harmonic balance, for the total
  // interval to hold (docs/identify.md, "Coverage, measured"): printed only.
  for (std::size_t j = 0; j < 3; ++j) {
    const std::string& name = study.parameters[j].name;
    EXPECT_GE(study.Coverage(j), 0.90) << name;
    EXPECT_GE(study.RmsZ(j), 0.8) << name << ": intervals too wide";
    EXPECT_LE(study.RmsZ(j), 1.25) << name << ": intervals too narrow";
  }
}

}  // namespace
}  // namespace beamid::solver
