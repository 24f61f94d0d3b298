// Diagnosis on campaigns from the independent time-domain simulator, each
// with one effect the base model leaves out, concealed (the campaign states
// the nominal set-up): the diagnosis names it first, the weighted residual
// drops at least 5x, and the held-out accelerometer (acc3) is predicted
// better. Three levels, nine steps around the resonance, realistic noise.
#include "solver/diagnosis.h"

#include <algorithm>
#include <cmath>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "tests/support/concealed_diagnosis.h"

namespace beamid::solver {
namespace {

using testing::DiagnoseScenario;
using testing::ExpectNamed;

double Extra(const DiagnosisResult& result, const std::string& name) {
  return testing::FinalParameter(result, name).value;
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
  // Finite intervals (the covariance was once inverted in physical units,
  // where rounding gave ±1e143), and the mass and its place found within
  // 1 % and 1 mm. Not within the intervals (±0.04 g, ±0.13 mm): the fit
  // finds 30.06 g at 449.66 mm, with or without the beam's loss factor
  // refitted beside them; the clamp compliance likewise comes out 0.15 %
  // high, 16 of its σ. Not traced further: of the order of the simulator's
  // 40-element beam against the exact one (natural frequencies within 0.05 %).
  for (const std::string name : {"added_mass", "added_mass_position"}) {
    const ParameterEstimate p = testing::FinalParameter(result, name);
    EXPECT_TRUE(std::isfinite(p.std) && p.std < 0.01 * p.value) << name << " ± " << p.std;
  }
  EXPECT_NEAR(Extra(result, "added_mass"), 0.03, 0.01 * 0.03);
  EXPECT_NEAR(Extra(result, "added_mass_position"), 0.45, 1e-3);
  // A wrong candidate's intervals are finite too: on this campaign the clamp
  // compliance refit reported about ±1e142 on every parameter before.
  for (const auto& c : result.candidates) {
    if (c.name != "clamp_compliance" || !c.converged) continue;
    for (const auto& p : c.fit.parameters)
      EXPECT_TRUE(std::isfinite(p.std) && p.std < 1e3 * std::max(std::abs(p.value), 1.0)) << p.name << " ± " << p.std;
  }
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
