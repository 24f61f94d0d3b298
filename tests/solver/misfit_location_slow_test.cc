// The support's moment–rotation loops reconstructed from campaigns of the
// independent time-domain simulator (examples/scenarios, fewer steps): the
// concealed Jenkins element of paper_friction shows as dissipation growing
// faster than a viscous damper's and as hysteretic loop harmonics; the base
// physics of paper_base (cubic spring, viscous damper) shows neither.
#include "solver/misfit_location.h"

#include <cstdio>
#include <filesystem>

#include <gtest/gtest.h>

#include "hb/campaign_writer.h"
#include "hb/scenario.h"
#include "hb/stepped_sine.h"
#include "signal/campaign.h"
#include "signal/campaign_extractor.h"
#include "tests/support/temp_path.h"

namespace beamid::solver {
namespace {

// Steps around the first resonance (about 54 Hz), at the scenarios' three
// force levels: amplitudes from well below to well above the slip rotation.
const std::vector<double> kFrequenciesHz{52.5, 54.0, 55.0, 56.0};

FitData SimulateAndExtract(const std::string& scenario_file, const std::string& name) {
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
  const signal::Campaign campaign = signal::ReadCampaign(folder);
  signal::ExtractOptions extract;
  extract.estimator.num_harmonics = 5;
  const signal::PhasorSet phasors = signal::ExtractCampaign(campaign, extract);
  FitData data = MakeFitData(campaign, phasors, {.num_fit_harmonics = 5});
  std::filesystem::remove_all(folder);
  return data;
}

class SupportLoopsOnSimulatedCampaigns : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    base_ = new FitData(SimulateAndExtract("examples/scenarios/paper_base.json", "base"));
    friction_ = new FitData(SimulateAndExtract("examples/scenarios/paper_friction.json", "friction"));
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
  static FitData* base_;
  static FitData* friction_;
};

FitData* SupportLoopsOnSimulatedCampaigns::base_ = nullptr;
FitData* SupportLoopsOnSimulatedCampaigns::friction_ = nullptr;

TEST_F(SupportLoopsOnSimulatedCampaigns, FrictionDissipatesFasterThanViscousAndBendsTheLoops) {
  const LoopEvidence loops = AnalyseSupportLoops(*friction_, Reference(*friction_));
  Print("paper_friction", loops);
  EXPECT_TRUE(loops.dissipation_not_viscous);
  EXPECT_GT(loops.damping_ratio_high_to_low, 1.5);
  EXPECT_GT(loops.area_exponent - 3.0 * loops.area_exponent_std, 2.0);
  EXPECT_TRUE(loops.hysteretic_shape);
}

TEST_F(SupportLoopsOnSimulatedCampaigns, BasePhysicsLoopsAreThoseOfAViscousDamper) {
  const LoopEvidence loops = AnalyseSupportLoops(*base_, Reference(*base_));
  Print("paper_base", loops);
  EXPECT_FALSE(loops.dissipation_not_viscous);
  EXPECT_NEAR(loops.mean_equivalent_damping_Nms_rad, 0.05, 0.005);
  EXPECT_FALSE(loops.hysteretic_shape);
  EXPECT_FALSE(loops.asymmetric);
}

}  // namespace
}  // namespace beamid::solver
