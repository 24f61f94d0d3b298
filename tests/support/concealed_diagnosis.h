// Test support for the diagnosis proofs: a scenario simulated by
// the independent time-domain simulator with one concealed effect, fitted on
// acc1 and acc2 (harmonics 1..3), held out on acc3, the fitted channels
// located up to the 5th harmonic; and the checks every proof shares.
#pragma once

#include <cstdio>
#include <filesystem>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "solver/diagnosis/diagnosis.h"
#include "tests/support/simulated_campaign.h"

namespace beamid::testing {

constexpr double kMinResidualDrop = 5.0;

inline solver::DiagnosisResult DiagnoseScenario(const nlohmann::json& scenario, const std::string& name,
                                                solver::DiagnosisOptions options = {}) {
  const ExtractedCampaign campaign = SimulateCampaign(scenario, "beamid_diagnosis_" + name);
  options.num_workers = 2;
  solver::DiagnosisResult result = solver::Diagnose(campaign.Fit({"acc1", "acc2"}), campaign.Fit({"acc3"}),
                                                    campaign.Fit({"acc1", "acc2"}, 5), options);
  std::filesystem::remove_all(campaign.folder);
  std::printf("%s: verdict '%s', selected %s, %.2f s\n", name.c_str(), ToString(result.verdict).c_str(),
              result.selected.front().c_str(), result.seconds);
  std::printf("  base: chi2 %.4g (reduced %.3g), held-out acc3 h1 %.3f %%, chi2 %.4g\n", result.base.chi_square,
              result.base.reduced_chi_square, 100 * result.base.held_out_h1_relative_error,
              result.base.held_out_chi_square);
  for (const auto& c : result.candidates)
    std::printf("  %-20s chi2 %.4g drop %.3gx BIC %.5g p %.2g held-out h1 %.3f %% chi2 %.4g score %.2f %s\n",
                c.name.c_str(), c.fit.chi_square, c.residual_drop, c.fit.bic, c.p_value,
                100 * c.fit.held_out_h1_relative_error, c.fit.held_out_chi_square, c.signature_score,
                c.significant ? "significant" : "");
  for (const auto& p : result.final_fit.parameters)
    std::printf("  %-20s %.6g ± %.2g (95 %%: %.6g … %.6g) %s\n", p.name.c_str(), p.value, 1.96 * p.std, p.lower_95,
                p.upper_95, p.unit.c_str());
  std::printf("  %s\n", result.summary.c_str());
  return result;
}

// What "the held-out accelerometer is predicted better" is measured by: the
// first harmonic's relative error, or the whitened χ² over the harmonics
// 1..K the model predicts (an effect that lives in the even harmonics barely
// moves the first).
enum class HeldOut { kFirstHarmonic, kHarmonicsChiSquare };

// blame: the model for missing physics (never taken for a fault of the
// recording), the recording for a measurement artefact.
inline void ExpectNamed(const solver::DiagnosisResult& result, const std::string& cause,
                        HeldOut held_out = HeldOut::kFirstHarmonic, solver::Blame blame = solver::Blame::kModel) {
  ASSERT_EQ(result.verdict, solver::DiagnosisVerdict::kCauseNamed);
  EXPECT_EQ(result.blame, blame);
  ASSERT_FALSE(result.selected.empty());
  EXPECT_EQ(result.selected.front(), cause);
  EXPECT_EQ(result.candidates.front().name, cause);
  EXPECT_GE(result.base.chi_square / result.final_fit.chi_square, kMinResidualDrop);
  if (held_out == HeldOut::kFirstHarmonic)
    EXPECT_LT(result.final_fit.held_out_h1_relative_error, result.base.held_out_h1_relative_error);
  else
    EXPECT_LT(result.final_fit.held_out_chi_square, result.base.held_out_chi_square);
}

inline solver::ParameterEstimate FinalParameter(const solver::DiagnosisResult& result, const std::string& name) {
  for (const auto& p : result.final_fit.parameters)
    if (p.name == name) return p;
  ADD_FAILURE() << "no parameter " << name;
  return {};
}

// The truth lies within the reported 95 % interval, and the interval is finite.
inline void ExpectWithinInterval(const solver::DiagnosisResult& result, const std::string& name, double truth) {
  const solver::ParameterEstimate p = FinalParameter(result, name);
  EXPECT_TRUE(std::isfinite(p.std) && p.std < std::abs(truth)) << name << " ± " << p.std;
  EXPECT_LE(p.lower_95, truth) << name;
  EXPECT_GE(p.upper_95, truth) << name;
}

}  // namespace beamid::testing
