// Diagnosis on campaigns from the independent time-domain simulator, each
// with one effect the base model leaves out, concealed (the campaign states
// the nominal set-up): the diagnosis names it first, the weighted residual
// drops at least 5x, and the held-out accelerometer (acc3) is predicted
// better. Three levels, nine steps around the resonance, realistic noise.
#include "solver/diagnosis.h"

#include <cstdio>
#include <filesystem>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "tests/support/simulated_campaign.h"

namespace beamid::solver {
namespace {

constexpr double kMinResidualDrop = 5.0;

DiagnosisResult DiagnoseScenario(const nlohmann::json& scenario, const std::string& name) {
  const testing::ExtractedCampaign campaign = testing::SimulateCampaign(scenario, "beamid_diagnosis_" + name);
  DiagnosisOptions options;
  options.num_workers = 2;
  DiagnosisResult result = Diagnose(campaign.Fit({"acc1", "acc2"}), campaign.Fit({"acc3"}),
                                    campaign.Fit({"acc1", "acc2"}, 5), options);
  std::filesystem::remove_all(campaign.folder);
  std::printf("%s: verdict '%s', selected %s, %.2f s\n", name.c_str(), result.verdict.c_str(),
              result.selected.front().c_str(), result.seconds);
  std::printf("  base: chi2 %.4g (reduced %.3g), held-out acc3 h1 %.3f %%\n", result.base.chi_square,
              result.base.reduced_chi_square, 100 * result.base.held_out_h1_relative_error);
  for (const auto& c : result.candidates)
    std::printf("  %-20s chi2 %.4g drop %.3gx BIC %.5g p %.2g held-out %.3f %% score %.2f %s\n", c.name.c_str(),
                c.fit.chi_square, c.residual_drop, c.fit.bic, c.p_value, 100 * c.fit.held_out_h1_relative_error,
                c.signature_score, c.significant ? "significant" : "");
  std::printf("  %s\n", result.summary.c_str());
  return result;
}

void ExpectNamed(const DiagnosisResult& result, const std::string& cause) {
  ASSERT_EQ(result.verdict, "cause named");
  ASSERT_FALSE(result.selected.empty());
  EXPECT_EQ(result.selected.front(), cause);
  EXPECT_EQ(result.candidates.front().name, cause);
  EXPECT_GE(result.base.chi_square / result.final_fit.chi_square, kMinResidualDrop);
  EXPECT_LT(result.final_fit.held_out_h1_relative_error, result.base.held_out_h1_relative_error);
}

double Extra(const DiagnosisResult& result, const std::string& name) {
  for (const auto& p : result.final_fit.parameters)
    if (p.name == name) return p.value;
  ADD_FAILURE() << "no parameter " << name;
  return 0.0;
}

TEST(DiagnosisOnConcealedEffects, NamesFrictionAtTheSupport) {
  nlohmann::json s = testing::PaperSetUpScenario();
  s["support"]["polynomial"]["k1_Nm_rad"] = 100.0;
  s["support"]["jenkins"] = {{"stiffness_Nm_rad", 50.0}, {"slip_moment_Nm", 0.15}};
  s["timing"]["max_time_step_s"] = 9.765625e-06;
  s["timing"]["settle_min_s"] = 1.0;
  s["timing"]["settle_tolerance"] = 5e-4;
  const DiagnosisResult result = DiagnoseScenario(s, "friction");
  ExpectNamed(result, "support_friction");
  // The slip moment within a factor 1.5 of the truth (0.15 N·m).
  EXPECT_NEAR(std::log(Extra(result, "jenkins_slip_moment") / 0.15), 0.0, std::log(1.5));
}

TEST(DiagnosisOnConcealedEffects, NamesClampCompliance) {
  nlohmann::json s = testing::PaperSetUpScenario();
  s["attachments"] = {{"clamp_rotational_stiffness_Nm_rad", 1e4}};
  const DiagnosisResult result = DiagnoseScenario(s, "clamp");
  ExpectNamed(result, "clamp_compliance");
  EXPECT_NEAR(1.0 / Extra(result, "clamp_compliance"), 1e4, 0.3e4);
}

TEST(DiagnosisOnConcealedEffects, NamesAnAddedMass) {
  nlohmann::json s = testing::PaperSetUpScenario();
  s["attachments"] = {{"point_masses", {{{"position_m", 0.45}, {"mass_kg", 0.03}}}}};
  const DiagnosisResult result = DiagnoseScenario(s, "added_mass");
  ExpectNamed(result, "added_mass");
}

TEST(DiagnosisOnConcealedEffects, NamesAModulusError) {
  nlohmann::json s = testing::PaperSetUpScenario();
  s["beam"]["youngs_modulus_Pa"] = 2.0e11;
  s["nominal_beam"] = {{"youngs_modulus_Pa", 2.1e11}};
  const DiagnosisResult result = DiagnoseScenario(s, "modulus");
  ExpectNamed(result, "modulus_error");
  EXPECT_NEAR(Extra(result, "EI_scale"), 2.0 / 2.1, 0.01);
}

}  // namespace
}  // namespace beamid::solver
