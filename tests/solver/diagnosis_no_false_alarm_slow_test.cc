// No false alarm: on campaigns whose physics IS the base model (polynomial
// support, nominal beam), the diagnosis names no cause. One noise-free
// simulation of the time-domain simulator, written with ten noise seeds.
#include <cstdio>
#include <filesystem>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "solver/diagnosis.h"
#include "tests/support/simulated_campaign.h"

namespace beamid::solver {
namespace {

constexpr int kRealisations = 10;

const char* const kScenario = R"({
  "name": "diagnosis test: base physics",
  "beam": {"length_m": 0.6, "width_m": 0.04, "thickness_m": 0.005, "youngs_modulus_Pa": 2.1e11,
           "density_kg_m3": 7850, "loss_factor": 0.0002},
  "support": {"polynomial": {"k1_Nm_rad": 150, "k2_Nm_rad2": 0, "k3_Nm_rad3": 3e5, "c_Nms_rad": 0.05}},
  "excitation": {"channel": "force", "position_m": 0.57},
  "sensors": [{"channel": "acc1", "position_m": 0.1}, {"channel": "acc2", "position_m": 0.3},
              {"channel": "acc3", "position_m": 0.57}],
  "levels": [{"label": "low", "force_amplitude_N": 1.0, "frequencies_Hz": {"start": 51, "stop": 57, "step": 0.75}},
             {"label": "mid", "force_amplitude_N": 4.0, "frequencies_Hz": {"start": 51, "stop": 57, "step": 0.75}},
             {"label": "high", "force_amplitude_N": 9.0, "frequencies_Hz": {"start": 51, "stop": 57, "step": 0.75}}],
  "timing": {"sample_rate_Hz": 5120, "settle_min_s": 0.2, "settle_max_s": 4.0, "transient_s": 0.05, "record_s": 0.4},
  "noise": {"seed": 1, "clock_offset_ppm": 25,
            "default": {"relative_rms": 0.003, "absolute": 0.005, "adc_bits": 24, "adc_range": 500},
            "channels": {"force": {"relative_rms": 0.002, "absolute": 0.002, "adc_bits": 24, "adc_range": 50}}}
})";

TEST(DiagnosisOnBasePhysics, RaisesNoFalseAlarmOverTenNoiseRealisations) {
  const hb::Scenario scenario = hb::ParseScenario(kScenario, "diagnosis_no_false_alarm scenario");
  const std::vector<hb::SimulatedStep> steps = testing::SimulateSteps(scenario);
  int alarms = 0;
  for (int r = 0; r < kRealisations; ++r) {
    const testing::ExtractedCampaign campaign =
        testing::WriteAndExtract(scenario, steps, 1000 + r, "beamid_diagnosis_base_" + std::to_string(r));
    DiagnosisOptions options;
    options.num_workers = 2;
    const DiagnosisResult result = Diagnose(campaign.Fit({"acc1", "acc2"}), campaign.Fit({"acc3"}),
                                            campaign.Fit({"acc1", "acc2"}, 5), options);
    std::filesystem::remove_all(campaign.folder);
    const CandidateOutcome& best = result.candidates.front();
    std::printf("realisation %d: %s; base reduced chi2 %.3g; best candidate %s (drop %.3gx, p %.2g), %.2f s\n", r,
                result.verdict.c_str(), result.base.reduced_chi_square, best.name.c_str(), best.residual_drop,
                best.p_value, result.seconds);
    EXPECT_EQ(result.verdict, "no significant discrepancy") << result.summary;
    EXPECT_EQ(result.selected, std::vector<std::string>{"none"});
    if (result.selected.front() != "none") ++alarms;
  }
  EXPECT_EQ(alarms, 0);
}

}  // namespace
}  // namespace beamid::solver
