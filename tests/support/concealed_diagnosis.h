// Test support for the diagnosis proofs: a scenario simulated by
// the independent time-domain simulator with one concealed effect, fitted on
// acc1 and acc2 (harmonics 1..3), held out on acc3, the fitted channels
// located up to the 5th harmonic; and the checks every proof shares.
#pragma once

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "solver/diagnosis/diagnosis.h"
#include "tests/support/proof_diagnosis.h"
#include "tests/support/simulated_campaign.h"

namespace beamid::testing {

constexpr double kMinResidualDrop = 5.0;

inline solver::DiagnosisResult DiagnoseScenario(const nlohmann::json& scenario, const std::string& name,
                                                solver::DiagnosisOptions options = {},
                                                solver::FitDataOptions fit_options = {}) {
  const ExtractedCampaign campaign = SimulateCampaign(scenario, "beamid_diagnosis_" + name);
  solver::DiagnosisResult result =
      DiagnoseProofData(MakeProofData(campaign.campaign, campaign.phasors, fit_options), options);
  std::filesystem::remove_all(campaign.folder);
  std::printf("%s: verdict '%s', selected %s, %.2f s\n", name.c_str(), ToString(result.verdict).c_str(),
              result.selected.front().c_str(), result.seconds);
  std::printf("  base: chi2 %.4g (reduced %.3g), held-out acc3 h1 %.3f %%, chi2 %.4g\n", result.base.chi_square,
              result.base.reduced_chi_square, 100 * result.base.held_out_h1_relative_error,
              result.base.held_out_chi_square);
  for (const auto& c : result.candidates)
    std::printf("  %-20s chi2 %.4g drop %.3gx BIC %.5g p %.2g held-out h1 %.3f %% chi2 %.4g score %.2f %s [%s]\n",
                c.name.c_str(), c.fit.chi_square, c.residual_drop, c.fit.bic, c.p_value,
                100 * c.fit.held_out_h1_relative_error, c.fit.held_out_chi_square, c.signature_score,
                c.significant ? "significant" : "", c.status_message.c_str());
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
// The whitened misfits the response points keep (what the report's residual
// maps draw) are each model's own: over the fitted channels their squares
// sum to the χ² its optimiser reached.
inline void ExpectMisfitsSumToTheFits(const solver::DiagnosisResult& result) {
  double base = 0.0, final = 0.0;
  for (const auto& p : result.response) {
    if (p.held_out) continue;
    EXPECT_FALSE(p.base_misfit_sigma.empty());
    EXPECT_EQ(p.final_misfit_sigma.size(), p.base_misfit_sigma.size());
    for (double m : p.base_misfit_sigma) base += m * m;
    for (double m : p.final_misfit_sigma) final += m * m;
  }
  EXPECT_NEAR(base, result.base.chi_square, 1e-6 * result.base.chi_square);
  EXPECT_NEAR(final, result.final_fit.chi_square, 1e-6 * result.final_fit.chi_square);
}

// Named physics comes with its model's backbone at the first fitted sensor,
// within the band the steps span (widened by a tenth each way: the backbone
// runs to 1.3 times the largest fitted amplitude).
inline void ExpectSelectedBackbone(const solver::DiagnosisResult& result) {
  const solver::SelectedBackbone& backbone = result.final_backbone;
  EXPECT_TRUE(backbone.error.empty()) << backbone.error;
  ASSERT_FALSE(backbone.points.empty());
  ASSERT_FALSE(result.response.empty());
  EXPECT_EQ(backbone.channel, result.response.front().channel);
  double lowest = result.response.front().frequency_hz, highest = lowest;
  for (const auto& p : result.response) {
    lowest = std::min(lowest, p.frequency_hz);
    highest = std::max(highest, p.frequency_hz);
  }
  for (const auto& p : backbone.points) {
    EXPECT_GT(p.amplitude_m, 0.0);
    EXPECT_GT(p.frequency_hz, 0.9 * lowest);
    EXPECT_LT(p.frequency_hz, 1.1 * highest);
  }
}

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
  ExpectMisfitsSumToTheFits(result);
  if (blame == solver::Blame::kModel) ExpectSelectedBackbone(result);
}

inline solver::ParameterEstimate FinalParameter(const solver::DiagnosisResult& result, const std::string& name) {
  for (const auto& p : result.final_fit.parameters)
    if (p.name == name) return p;
  ADD_FAILURE() << "no parameter " << name;
  return {};
}

// The truth lies within the reported 95 % interval, and the interval is no
// wider than the data allow: a standard uncertainty above max_relative_std of
// the truth would be an interval that holds the truth by being vague.
inline void ExpectIntervalHolds(const solver::ParameterEstimate& p, double truth, double max_relative_std) {
  EXPECT_TRUE(std::isfinite(p.std) && p.std <= max_relative_std * std::abs(truth))
      << p.name << " ± " << p.std << ", at most " << max_relative_std * std::abs(truth);
  EXPECT_LE(p.lower_95, truth) << p.name;
  EXPECT_GE(p.upper_95, truth) << p.name;
}

// A named cause's parameter; each caller states its bound (about twice the
// standard uncertainty measured on its campaign). When the selected model's
// damping laws were refitted, its total interval (damping laws, harmonic
// truncation) holds the truth too, and is at most 3× the statistical one:
// these campaigns' physics is the model's once the cause is named.
inline void ExpectWithinInterval(const solver::DiagnosisResult& result, const std::string& name, double truth,
                                 double max_relative_std) {
  ExpectIntervalHolds(FinalParameter(result, name), truth, max_relative_std);
  if (result.blame == solver::Blame::kModel) {
    EXPECT_FALSE(result.final_damping_laws.intervals.empty()) << "the named physics carries no total intervals";
  }
  for (const auto& total : result.final_damping_laws.intervals)
    if (total.name == name) {
      EXPECT_LE(total.lower_95, truth) << name << "'s total interval";
      EXPECT_GE(total.upper_95, truth) << name << "'s total interval";
      EXPECT_LE(total.WidthRatio(), 3.0) << name << "'s total interval, " << total.lower_95 << " … "
                                         << total.upper_95;
    }
}

}  // namespace beamid::testing
