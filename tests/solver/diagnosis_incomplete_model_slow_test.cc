// Identification and diagnosis when the model lacks physics the rig has
//, on campaigns from the independent time-domain simulator with
// the paper's set-up, three levels of nine steps, realistic noise, a clock
// offset and a distorted force (2 % second and 1 % third harmonic, as a
// shaker on a nonlinear beam gives), acc1 and acc2 fitted and acc3 (at the
// drive point) held out:
// - unreported masses at the three instruments (the shaker's moving part and
//   the transducer at the drive point, both accelerometers heavier than
//   stated): identify still returns its fit, with the verdict that it misses
//   the data; the diagnosis names the masses at the instruments, not one mass
//   somewhere, and finds each within its interval;
// - friction at the support AND a compliant clamp: friction alone leaves a
//   misfit beyond the noise, which the diagnosis says, and then names the pair
//   with both effects' parameters near the truth.
#include <cstdio>
#include <filesystem>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "solver/diagnosis/diagnosis.h"
#include "solver/estimation/identify.h"
#include "tests/support/concealed_diagnosis.h"

namespace beamid::solver {
namespace {

using testing::DiagnoseScenario;

nlohmann::json WithDistortedForce(nlohmann::json s) {
  s["excitation"]["distortion"] = {{{"harmonic", 2}, {"amplitude_ratio", 0.02}, {"phase_rad", 0.4}},
                                   {{"harmonic", 3}, {"amplitude_ratio", 0.01}, {"phase_rad", -1.1}}};
  return s;
}

TEST(DiagnosisOfAnIncompleteModel, IdentifyAnswersAndDiagnoseNamesTheMassesAtTheInstruments) {
  nlohmann::json s = WithDistortedForce(testing::PaperSetUpScenario());
  s["attachments"] = {{"point_masses",
                       {{{"position_m", 0.57}, {"mass_kg", 0.015}},
                        {{"position_m", 0.1}, {"mass_kg", 0.004}},
                        {{"position_m", 0.3}, {"mass_kg", 0.003}}}}};
  {
    const testing::ExtractedCampaign campaign = testing::SimulateCampaign(s, "beamid_instrument_masses_identify");
    ModelStructure structure = PolynomialModel({.k1_Nm_rad = 100.0});
    structure.linear.push_back(LossFactor(1e-4));
    IdentifyResult result;
    ASSERT_NO_THROW(result = Identify(campaign.Fit({"acc1", "acc2"}), structure, {}));
    std::printf("identify: reduced chi-square %.3g, %s\n", result.reduced_chi_square, result.verdict.text.c_str());
    EXPECT_FALSE(result.verdict.within_noise);
    EXPECT_NE(result.verdict.text.find("beamid diagnose"), std::string::npos);
    std::filesystem::remove_all(campaign.folder);
  }
  const DiagnosisResult result = DiagnoseScenario(s, "instrument_masses");
  testing::ExpectNamed(result, "instrument_masses");
  EXPECT_TRUE(result.rest_within_noise);
  EXPECT_NE(result.summary.find("On the rig: weigh the shaker's moving part"), std::string::npos) << result.summary;
  // Bounds about twice the measured standard uncertainties: these data hold
  // the drive's and acc1's masses loosely (15 % and 16 %), acc2's well (1.3 %).
  testing::ExpectWithinInterval(result, "mass_at_drive", 0.015, 0.3);
  testing::ExpectWithinInterval(result, "mass_at_acc1", 0.004, 0.3);
  testing::ExpectWithinInterval(result, "mass_at_acc2", 0.003, 0.03);
}

TEST(DiagnosisOfAnIncompleteModel, FrictionAloneLeavesAMisfitAndThePairWithClampComplianceIsNamed) {
  nlohmann::json s = WithDistortedForce(testing::PaperSetUpScenario());
  testing::AddSupportFriction(s, 100.0, 50.0, 0.15);
  s["attachments"] = {{"clamp_rotational_stiffness_Nm_rad", 3e4}};
  const DiagnosisResult result = DiagnoseScenario(s, "friction_and_clamp");
  ASSERT_EQ(result.verdict, DiagnosisVerdict::kCombinationNamed);
  ASSERT_EQ(result.selected.size(), 2u);
  EXPECT_EQ(result.selected[0], "support_friction");
  EXPECT_EQ(result.selected[1], "clamp_compliance");
  ASSERT_FALSE(result.candidates.empty());
  EXPECT_EQ(result.candidates.front().name, "support_friction");
  EXPECT_GT(result.candidates.front().fit.reduced_chi_square, DiagnosisOptions{}.acceptable_reduced_chi_square)
      << "friction alone should leave a misfit";
  EXPECT_TRUE(result.rest_within_noise);
  EXPECT_LT(result.final_fit.held_out_h1_relative_error, result.candidates.front().fit.held_out_h1_relative_error);
  // Within 1 % (the steps settle to 5e-4 only, as in the friction proof).
  EXPECT_NEAR(testing::FinalParameter(result, "jenkins_stiffness").value, 50.0, 0.01 * 50.0);
  EXPECT_NEAR(testing::FinalParameter(result, "jenkins_slip_moment").value, 0.15, 0.01 * 0.15);
  EXPECT_NEAR(testing::FinalParameter(result, "clamp_compliance").value, 1.0 / 3e4, 0.02 / 3e4);
}

}  // namespace
}  // namespace beamid::solver
