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
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "hb/noise.h"
#include "hb/scenario.h"
#include "hb/stepped_sine.h"
#include "signal/campaign.h"
#include "signal/phasor_estimator.h"
#include "solver/estimation/identify.h"
#include "tests/support/coverage_study.h"
#include "tests/support/simulated_campaign.h"
#include "tests/support/temp_path.h"

namespace beamid::solver {
namespace {

constexpr int kRealisations = 30;
constexpr double kMinCoverage = 0.85;  // the 85–100 %
const std::vector<std::string> kNames = {"k1", "k2", "k3", "c", "loss_factor"};
const std::vector<double> kTruth = {150.0, 0.0, 3e5, 0.05, 2e-4};

TEST(IdentificationCoverage, TruthLiesInThe95PercentIntervalsIn85To100PercentOfNoiseRealisations) {
  const hb::Scenario scenario = beamid::testing::LeanPaperBase();
  ASSERT_EQ(scenario.NumSteps(), 45);
  const std::filesystem::path folder = beamid::testing::UniqueTempPath("beamid_coverage_slow_test");
  std::filesystem::remove_all(folder);
  // campaign.json (and truth.json) once; the recordings are re-noised below.
  const std::vector<hb::SimulatedStep> steps = beamid::testing::SimulateInto(scenario, folder);
  const signal::Campaign campaign = signal::ReadCampaign(folder);
  std::filesystem::remove_all(folder);

  ModelStructure structure = PolynomialModel({.k1_Nm_rad = 100.0});
  structure.linear.push_back(LossFactor(1e-4));  // as `beamid identify` fits it by default
  std::vector<int> covered(kNames.size(), 0);
  std::vector<double> sum_z(kNames.size(), 0.0), sum_z2(kNames.size(), 0.0);
  for (int r = 0; r < kRealisations; ++r) {
    const signal::PhasorSet phasors = beamid::testing::MeasureAgain(scenario, steps, campaign, 1000 + r);
    const FitData fit = MakeFitData(campaign, phasors, {.channels = {"acc1", "acc2"}});
    const IdentifyResult result = Identify(fit, structure, {});
    ASSERT_EQ(result.parameters.size(), kNames.size());
    for (std::size_t j = 0; j < kNames.size(); ++j) {
      const ParameterEstimate& p = result.parameters[j];
      ASSERT_EQ(p.name, kNames[j]);
      const double z = (p.value - kTruth[j]) / p.std;
      sum_z[j] += z;
      sum_z2[j] += z * z;
      if (p.lower_95 <= kTruth[j] && kTruth[j] <= p.upper_95) ++covered[j];
    }
    // The first check, on every realisation.
    EXPECT_NEAR(result.parameters[0].value, kTruth[0], 0.01 * kTruth[0]) << "realisation " << r;
    EXPECT_NEAR(result.parameters[2].value, kTruth[2], 0.10 * kTruth[2]) << "realisation " << r;
    EXPECT_NEAR(result.parameters[3].value, kTruth[3], 0.05 * kTruth[3]) << "realisation " << r;
    EXPECT_LE(result.parameters[1].lower_95, kTruth[1]) << "k2, realisation " << r;
    EXPECT_GE(result.parameters[1].upper_95, kTruth[1]) << "k2, realisation " << r;
  }
  for (std::size_t j = 0; j < kNames.size(); ++j) {
    const double coverage = static_cast<double>(covered[j]) / kRealisations;
    const double mean_z = sum_z[j] / kRealisations;
    const double rms_z = std::sqrt(sum_z2[j] / kRealisations);
    std::printf("%-12s coverage %5.1f %% (%d of %d), bias/sigma %+.2f, rms (estimate - truth)/sigma %.2f\n",
                kNames[j].c_str(), 100.0 * coverage, covered[j], kRealisations, mean_z, rms_z);
    EXPECT_GE(coverage, kMinCoverage) << kNames[j] << ": mean (estimate - truth)/sigma " << mean_z;
    EXPECT_LE(coverage, 1.0) << kNames[j];
  }
}

// 50 realisations: rms z has a sampling σ of about 1/√100 = 0.1.
TEST(IdentificationCoverage, PropagatedIntervalsOfTheStiffnessesAreNeitherTooWideNorTooNarrowOnExactPhysics) {
  const beamid::testing::CoveragePhysics physics = beamid::testing::MakeCoveragePhysics("rayleigh");
  const beamid::testing::CoverageStudy study =
      beamid::testing::RunCoverageStudy(physics, {.uncertainty = PhasorUncertainty::kPropagated}, 50, 1000);
  for (std::size_t j = 0; j < study.parameters.size(); ++j)
    std::printf("%-22s coverage %5.1f %%, mean z %+.2f, rms z %.2f\n", study.parameters[j].name.c_str(),
                100.0 * study.Coverage(j), study.MeanZ(j), study.RmsZ(j));
  // k1, k2, k3. The damping parameters (c, α, β) still scatter ~1.3× their σ
  // (docs/identify.md, "How each phasor is weighed"), so they are printed only.
  for (std::size_t j = 0; j < 3; ++j) {
    const std::string& name = study.parameters[j].name;
    EXPECT_GE(study.Coverage(j), 0.90) << name;
    EXPECT_GE(study.RmsZ(j), 0.8) << name << ": intervals too wide";
    EXPECT_LE(study.RmsZ(j), 1.25) << name << ": intervals too narrow";
  }
}

}  // namespace
}  // namespace beamid::solver
