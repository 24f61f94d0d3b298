// The support's moment–rotation loops reconstructed from campaigns of the
// independent time-domain simulator (examples/scenarios, fewer steps): the
// concealed Jenkins element of paper_friction shows as dissipation growing
// faster than a viscous damper's and as hysteretic loop harmonics; the base
// physics of paper_base (cubic spring, viscous damper) shows neither.
#include "solver/diagnosis/misfit_location.h"

#include <cstdio>
#include <filesystem>

#include <gtest/gtest.h>

#include "hb/campaign_writer.h"
#include "hb/scenario.h"
#include "hb/stepped_sine.h"
#include "signal/campaign.h"
#include "signal/campaign_extractor.h"
#include "solver/estimation/identification_problem.h"
#include "solver/estimation/identify.h"
#include "solver/estimation/model_phasors.h"
#include "tests/support/temp_path.h"

namespace beamid::solver {
namespace {

// Steps around the first resonance (about 54 Hz), at the scenarios' three
// force levels: amplitudes from well below to well above the slip rotation.
const std::vector<double> kFrequenciesHz{52.5, 54.0, 55.0, 56.0};

struct SimulatedCampaign {
  signal::Campaign campaign;
  signal::PhasorSet phasors;
  FitData Data(std::vector<std::string> channels, int num_harmonics) const {
    return MakeFitData(campaign, phasors, {.channels = std::move(channels), .num_fit_harmonics = num_harmonics});
  }
};

SimulatedCampaign SimulateAndExtract(const std::string& scenario_file, const std::string& name) {
  hb::Scenario scenario = hb::ReadScenario(scenario_file);
  for (hb::ScenarioLevel& level : scenario.levels) level.frequencies_hz = kFrequenciesHz;
  scenario.timing.record_s = 0.3;
  const std::filesystem::path folder = beamid::testing::UniqueTempPath("beamid_misfit_location_slow_test_" + name);
  std::filesystem::remove_all(folder);
  {
    hb::SteppedSineSimulation simulation(scenario);
    hb::CampaignWriter writer(simulation, folder);
    simulation.Run([&](const hb::SimulatedStep& step) { writer.Write(step); });
    writer.Finish();
  }
  signal::Campaign campaign = signal::ReadCampaign(folder);
  signal::ExtractOptions extract;
  extract.estimator.num_harmonics = 5;
  signal::PhasorSet phasors = signal::ExtractCampaign(campaign, extract);
  std::filesystem::remove_all(folder);
  return {std::move(campaign), std::move(phasors)};
}

class SupportLoopsOnSimulatedCampaigns : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    base_ = new SimulatedCampaign(SimulateAndExtract("examples/scenarios/paper_base.json", "base"));
    friction_ = new SimulatedCampaign(SimulateAndExtract("examples/scenarios/paper_friction.json", "friction"));
  }
  static void TearDownTestSuite() {
    delete base_;
    delete friction_;
  }
  // The base model a fit at small amplitude finds: k1 = 150 N·m/rad in both
  // (the friction scenario's 100 plus its stuck Jenkins spring, 50), c = 0.05.
  static hb::LinearBeamModel Reference(const FitData& data) {
    return {.beam = data.beam,
            .attachments = data.sensor_masses,
            .support_stiffness_Nm_rad = 150.0,
            .support_damping_Nms_rad = 0.05};
  }
  static void Print(const char* name, const LoopEvidence& loops) {
    std::printf("%s: %d steps used; area exponent %.2f ± %.2f; c_eq high/low %.2f; viscous chi2 %.1f / %d (p %.2g);"
                " hysteretic harmonics chi2 %.1f, elastic %.1f / %d; theta even chi2 %.1f / %d\n",
                name, loops.num_steps_used, loops.area_exponent, loops.area_exponent_std,
                loops.damping_ratio_high_to_low, loops.viscous_chi2, loops.viscous_dof, loops.viscous_p_value,
                loops.hysteretic_harmonic_chi2, loops.elastic_harmonic_chi2, loops.harmonic_dof, loops.theta_even_chi2,
                loops.theta_even_dof);
    for (const LoopStep& s : loops.steps)
      std::printf("  %-4s %.2f Hz |θ1| %.3e ± %.1e rad  W %.3e ± %.1e J (viscous %.3e)  c_eq %.4f ± %.4f  M~k/M1 %.3f\n",
                  s.level.c_str(), s.omega_rad_s / (2 * std::numbers::pi), s.theta_amplitude_rad, s.theta_std_rad,
                  s.dissipated_energy_J, s.dissipated_energy_std_J, s.viscous_energy_J, s.equivalent_damping_Nms_rad,
                  s.equivalent_damping_std_Nms_rad, s.moment_harmonic_ratio);
  }
  static SimulatedCampaign* base_;
  static SimulatedCampaign* friction_;
};

SimulatedCampaign* SupportLoopsOnSimulatedCampaigns::base_ = nullptr;
SimulatedCampaign* SupportLoopsOnSimulatedCampaigns::friction_ = nullptr;

const std::vector<std::string> kAllChannels{"acc1", "acc2", "acc3"};

TEST_F(SupportLoopsOnSimulatedCampaigns, FrictionDissipatesFasterThanViscousAndBendsTheLoops) {
  const FitData data = friction_->Data(kAllChannels, 5);
  const LoopEvidence loops = AnalyseSupportLoops(data, Reference(data));
  Print("paper_friction", loops);
  EXPECT_TRUE(loops.dissipation_not_viscous);
  EXPECT_GT(loops.damping_ratio_high_to_low, 1.5);
  EXPECT_GT(loops.area_exponent - 3.0 * loops.area_exponent_std, 2.0);
  EXPECT_TRUE(loops.hysteretic_shape);
}

TEST_F(SupportLoopsOnSimulatedCampaigns, BasePhysicsLoopsAreThoseOfAViscousDamper) {
  const FitData data = base_->Data(kAllChannels, 5);
  const LoopEvidence loops = AnalyseSupportLoops(data, Reference(data));
  Print("paper_base", loops);
  EXPECT_FALSE(loops.dissipation_not_viscous);
  EXPECT_NEAR(loops.mean_equivalent_damping_Nms_rad, 0.05, 0.005);
  EXPECT_FALSE(loops.hysteretic_shape);
  EXPECT_FALSE(loops.asymmetric);
}

// The base model (polynomial support) fitted to acc1 and acc2, harmonics
// 1..3; the misfit located on all three accelerometers, harmonics 1..5.
MisfitLocation FitBaseModelAndLocate(const SimulatedCampaign& campaign) {
  const FitData fit = campaign.Data({"acc1", "acc2"}, 3);
  // Started from the paper's values, not from the direct estimate (which the
  // friction distorts).
  ModelStructure structure = PolynomialModel({.k1_Nm_rad = 150.0, .k3_Nm_rad3 = 3e5, .c_Nms_rad = 0.05});
  IdentifyOptions options;
  options.model.num_harmonics = 5;
  options.use_direct_estimate = false;
  options.ipopt.max_iterations = 1000;
  const IdentifyResult result = Identify(fit, structure, options);
  IdentificationProblem problem(fit, structure, options.model);
  problem.FeasiblePoint(result.starts[result.best_start].scaled_at);
  const FitData examined = campaign.Data(kAllChannels, 5);
  const std::vector<Eigen::MatrixXcd> model = ModelPhasors(examined, problem, result.x);
  std::vector<double> values;
  for (const auto& p : result.parameters) values.push_back(p.value);
  structure.SetValues(values);
  hb::LinearBeamModel reference = structure.ApplyLinear({.beam = examined.beam, .attachments = examined.sensor_masses});
  reference.support_stiffness_Nm_rad = values[0];
  reference.support_damping_Nms_rad = values[3];
  for (const auto& p : result.parameters) std::printf("%s = %.6g ± %.3g\n", p.name.c_str(), p.value, p.std);
  std::printf("reduced chi-square %.3g\n", result.reduced_chi_square);
  const MisfitLocation location =
      LocateMisfit(examined, model, 3, reference, {.num_fitted_parameters = static_cast<int>(values.size())});
  for (const auto& f : location.findings) std::printf("  %s\n", f.c_str());
  return location;
}

TEST_F(SupportLoopsOnSimulatedCampaigns, TheFittedBaseModelMissesTheFrictionCampaign) {
  const MisfitLocation location = FitBaseModelAndLocate(*friction_);
  EXPECT_TRUE(location.significant);
  EXPECT_TRUE(location.loops.dissipation_not_viscous);
  EXPECT_TRUE(location.loops.hysteretic_shape);
  ASSERT_FALSE(location.findings.empty());
  EXPECT_NE(location.findings.back().find("evidence of friction"), std::string::npos) << location.findings.back();
}

TEST_F(SupportLoopsOnSimulatedCampaigns, TheFittedBaseModelExplainsTheBaseCampaign) {
  const MisfitLocation location = FitBaseModelAndLocate(*base_);
  EXPECT_FALSE(location.significant);
  EXPECT_FALSE(location.loops.dissipation_not_viscous);
  EXPECT_FALSE(location.loops.hysteretic_shape);
  ASSERT_FALSE(location.findings.empty());
  EXPECT_NE(location.findings[0].find("No significant discrepancy"), std::string::npos) << location.findings[0];
}

}  // namespace
}  // namespace beamid::solver
