// Selection that validates without a held-out sensor: when every
// accelerometer is fitted, each level is left out in turn, the model refitted
// to the others and judged on the level it did not see. On campaigns of the
// independent time-domain simulator (the paper's set-up, three levels of
// nine steps, noise, a clock offset), acc1, acc2 and acc3 all fitted:
// - a beam whose Young's modulus is 4.8 % below the nominal: the diagnosis
//   is ranked by the levels left out, names the modulus error (alone or as
//   one of two the data cannot tell apart), and the named model predicts the
//   left-out levels far better than the base;
// - the base physics: the base predicts the left-out levels within their
//   noise, and nothing is named.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "solver/diagnosis/diagnosis.h"
#include "tests/support/simulated_campaign.h"

namespace beamid::solver {
namespace {

DiagnosisResult DiagnoseWithoutHeldOutChannel(const nlohmann::json& scenario, const std::string& name) {
  const testing::ExtractedCampaign campaign = testing::SimulateCampaign(scenario, "beamid_left_out_levels_" + name);
  DiagnosisOptions options;
  options.num_workers = 2;
  const FitData fit = campaign.Fit({"acc1", "acc2", "acc3"});
  std::filesystem::remove_all(campaign.folder);
  DiagnosisResult result = Diagnose(fit, FitData{}, FitData{}, options);
  std::printf("%s: verdict '%s', ranked by %s, selected %s, %.1f s\n", name.c_str(), ToString(result.verdict).c_str(),
              ToString(result.ranked_by).c_str(), result.selected.front().c_str(), result.seconds);
  std::printf("  base: chi2 %.4g, left-out levels chi2 %.4g over %d (h1 %.3f %%)\n", result.base.chi_square,
              result.base.held_out_chi_square, result.base.held_out_num_residuals,
              100 * result.base.held_out_h1_relative_error);
  for (const auto& c : result.candidates)
    std::printf("  %-28s chi2 %.4g BIC %.6g left-out chi2 %.4g (h1 %.3f %%) %s\n", c.name.c_str(), c.fit.chi_square,
                c.fit.bic, c.fit.held_out_chi_square, 100 * c.fit.held_out_h1_relative_error,
                c.significant ? "significant" : "");
  std::printf("  %s\n", result.summary.c_str());
  return result;
}

TEST(DiagnosisOnLeftOutLevels, ModulusErrorValidatedWithoutAHeldOutSensor) {
  nlohmann::json s = testing::PaperSetUpScenario();
  s["beam"]["youngs_modulus_Pa"] = 2.0e11;
  s["nominal_beam"] = {{"youngs_modulus_Pa", 2.1e11}};
  const DiagnosisResult result = DiagnoseWithoutHeldOutChannel(s, "modulus");
  EXPECT_EQ(result.ranked_by, RankedBy::kLevelsLeftOut);
  ASSERT_FALSE(result.selected.empty());
  ASSERT_TRUE(result.verdict == DiagnosisVerdict::kCauseNamed ||
              result.verdict == DiagnosisVerdict::kCausesIndistinguishable)
      << result.verdict;
  EXPECT_TRUE(result.selected.front() == "modulus_error" ||
              (result.selected.size() > 1 && result.selected[1] == "modulus_error"))
      << result.summary;
  const auto named = std::find_if(result.candidates.begin(), result.candidates.end(),
                                  [](const CandidateOutcome& c) { return c.name == "modulus_error"; });
  ASSERT_NE(named, result.candidates.end());
  ASSERT_TRUE(std::isfinite(named->fit.held_out_chi_square));
  ASSERT_TRUE(std::isfinite(result.base.held_out_chi_square));
  // Judged on levels it did not see, the modulus error predicts them at least
  // ten times better than the base.
  EXPECT_LT(10.0 * named->fit.held_out_chi_square, result.base.held_out_chi_square);
  EXPECT_NE(result.summary.find("Levels left out in turn"), std::string::npos) << result.summary;
}

TEST(DiagnosisOnLeftOutLevels, BasePhysicsPredictsTheLeftOutLevelsWithinTheNoise) {
  const DiagnosisResult result = DiagnoseWithoutHeldOutChannel(testing::PaperSetUpScenario(), "base");
  EXPECT_EQ(result.verdict, DiagnosisVerdict::kNoSignificantDiscrepancy);
  ASSERT_TRUE(std::isfinite(result.base.held_out_chi_square));
  ASSERT_GT(result.base.held_out_num_residuals, 0);
  // χ² of n residuals the fit did not see: mean n, σ √(2n); 2n is far beyond.
  EXPECT_LT(result.base.held_out_chi_square, 2.0 * result.base.held_out_num_residuals);
}

}  // namespace
}  // namespace beamid::solver
