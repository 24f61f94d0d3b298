// Do the phasors' stated uncertainties mean what they say? On campaigns
// whose physics the model holds (the paper's set-up, base physics, from the
// independent time-domain simulator, re-noised as a real test of this beam
// would be: tests/support/simulated_campaign.h), χ² per fitted channel,
// harmonic and level, pooled over noise realisations, divided by its
// degrees of freedom is 1 within its sampling spread when each phasor's σ
// holds the record's noise and the force's and frequency's errors
// propagated into it (PhasorUncertainty::kPropagated). The
// relative floor (kRelativeFloor), the positive control, weighs the same
// residuals far below their noise, and the same check sees it.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <string>
#include <tuple>
#include <vector>

#include <gtest/gtest.h>

#include "solver/estimation/identify.h"
#include "solver/estimation/model_phasors.h"
#include "solver/estimation/whitened_misfit.h"
#include "tests/support/simulated_campaign.h"
#include "tests/support/temp_path.h"

namespace beamid::solver {
namespace {

constexpr int kRealisations = 8;

// χ² and its count of real residuals, per (channel, harmonic, level).
using Cell = std::tuple<std::string, int, std::string>;
struct Pooled {
  double chi_square = 0.0;
  int residuals = 0;
};

void AddFit(const FitData& fit, std::map<Cell, Pooled>* cells) {
  ModelStructure structure = PolynomialModel({.k1_Nm_rad = 100.0});
  structure.linear.push_back(LossFactor(1e-4));
  const IdentifyOptions options;
  const IdentifyResult result = Identify(fit, structure, options);
  const auto problem = options.family->MakeProblem(fit, structure, options.model);
  problem->FeasiblePoint(result.starts[static_cast<std::size_t>(result.best_start)].scaled_at);
  const std::vector<Eigen::MatrixXcd> model = ModelPhasors(fit, *problem, result.x);
  for (std::size_t i = 0; i < fit.steps.size(); ++i)
    for (int c = 0; c < static_cast<int>(fit.channels.size()); ++c)
      for (int k = 1; k <= fit.num_fit_harmonics; ++k) {
        const FitStep& s = fit.steps[i];
        Pooled& cell = (*cells)[{fit.channels[static_cast<std::size_t>(c)].channel, k, s.level}];
        cell.chi_square += Whitened(s, c, k, model[i](c, k - 1) - s.measured(c, k - 1)).squaredNorm();
        cell.residuals += 2;
      }
}

TEST(PhasorCalibration, ChiSquarePerChannelHarmonicAndLevelIsItsDegreesOfFreedomWhenTheInputsArePropagated) {
  const hb::Scenario scenario = beamid::testing::LeanPaperBase();
  const std::filesystem::path folder = beamid::testing::UniqueTempPath("beamid_phasor_calibration_slow_test");
  std::filesystem::remove_all(folder);
  const std::vector<hb::SimulatedStep> steps = beamid::testing::SimulateInto(scenario, folder);
  const signal::Campaign campaign = signal::ReadCampaign(folder);
  std::filesystem::remove_all(folder);

  std::map<Cell, Pooled> propagated, floor;
  for (int r = 0; r < kRealisations; ++r) {
    const signal::PhasorSet phasors = beamid::testing::MeasureAgain(scenario, steps, campaign, 2000 + r);
    AddFit(MakeFitData(campaign, phasors,
                       {.channels = {"acc1", "acc2"}, .uncertainty = PhasorUncertainty::kPropagated}),
           &propagated);
    AddFit(MakeFitData(campaign, phasors,
                       {.channels = {"acc1", "acc2"}, .uncertainty = PhasorUncertainty::kRelativeFloor}),
           &floor);
  }
  // Five parameters fitted to 18 cells of 240 residuals each: each cell
  // loses about 0.3 % of its degrees of freedom to them, left out here.
  for (const auto& [cell, p] : propagated) {
    const auto& [channel, k, level] = cell;
    const double reduced = p.chi_square / p.residuals;
    const double spread = std::sqrt(2.0 / p.residuals);  // σ of χ²/ν
    const double reduced_floor = floor.at(cell).chi_square / floor.at(cell).residuals;
    std::printf("%-5s h%d %-5s  chi2/nu propagated %.3f (spread %.3f)  floor %.3f\n", channel.c_str(), k,
                level.c_str(), reduced, spread, reduced_floor);
    EXPECT_NEAR(reduced, 1.0, 4.0 * spread) << channel << " h" << k << " " << level;
    // The control: with the floor the same residuals read far below 1.
    if (k >= 2) {
      EXPECT_LT(reduced_floor, 1.0 - 4.0 * spread) << channel << " h" << k << " " << level;
    }
  }
}

}  // namespace
}  // namespace beamid::solver
