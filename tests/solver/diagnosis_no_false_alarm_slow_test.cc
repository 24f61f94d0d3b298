// No false alarm: on campaigns whose physics IS the base model (polynomial
// support, nominal beam), the diagnosis names no cause. One noise-free
// simulation of the time-domain simulator, written with ten noise seeds.
// The positive control: the same recordings with acc1's gain off by 0.05 %
// (its phasors and their σ scaled, as a wrong calibration factor scales the
// record), just above what the diagnosis detects under the default
// weighting (measured on the first realisation: 0.02 % gives p = 0.05 against
// the 0.01/candidates needed, 0.04 % p = 1e-4), are named; a detector that
// always said "nothing" would pass the first half and fail this one.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "solver/diagnosis/diagnosis.h"
#include "tests/support/proof_diagnosis.h"
#include "tests/support/simulated_campaign.h"

namespace beamid::solver {
namespace {

constexpr int kRealisations = 10;
constexpr int kControls = 3;
constexpr double kControlGainError = 5e-4;

TEST(DiagnosisOnBasePhysics, RaisesNoFalseAlarmOverTenNoiseRealisations) {
  const hb::Scenario scenario =
      hb::ParseScenario(testing::PaperSetUpScenario().dump(), "diagnosis_no_false_alarm scenario");
  const std::vector<hb::SimulatedStep> steps = testing::SimulateSteps(scenario);
  int alarms = 0;
  std::vector<testing::ExtractedCampaign> controls;
  for (int r = 0; r < kRealisations; ++r) {
    const testing::ExtractedCampaign campaign =
        testing::WriteAndExtract(scenario, steps, 1000 + r, "beamid_diagnosis_base_" + std::to_string(r));
    const DiagnosisResult result =
        testing::DiagnoseProofData(testing::MakeProofData(campaign.campaign, campaign.phasors));
    std::filesystem::remove_all(campaign.folder);
    if (r < kControls) controls.push_back(campaign);
    const CandidateOutcome& best = result.candidates.front();
    std::printf("realisation %d: %s; base reduced chi2 %.3g; best candidate %s (drop %.3gx, p %.2g), %.2f s\n", r,
                ToString(result.verdict).c_str(), result.base.reduced_chi_square, best.name.c_str(), best.residual_drop,
                best.p_value, result.seconds);
    EXPECT_EQ(result.verdict, DiagnosisVerdict::kNoSignificantDiscrepancy) << result.summary;
    EXPECT_EQ(result.selected, std::vector<std::string>{"none"});
    EXPECT_EQ(result.blame, Blame::kNone) << "a clean recording blamed";
    EXPECT_TRUE(std::any_of(result.candidates.begin(), result.candidates.end(),
                            [](const CandidateOutcome& c) { return c.measurement && c.Refitted(); }))
        << "the recording's faults were not tried";
    if (result.selected.front() != "none") ++alarms;
  }
  EXPECT_EQ(alarms, 0);

  for (testing::ExtractedCampaign& campaign : controls) {
    for (signal::StepPhasors& step : campaign.phasors.steps)
      for (signal::ChannelPhasors& response : step.responses)
        if (response.channel == "acc1")
          for (signal::HarmonicPhasor& h : response.harmonics) {
            h.value *= 1.0 + kControlGainError;
            h.std_real *= 1.0 + kControlGainError;
            h.std_imag *= 1.0 + kControlGainError;
          }
    const DiagnosisResult result =
        testing::DiagnoseProofData(testing::MakeProofData(campaign.campaign, campaign.phasors));
    std::printf("control: %s; base reduced chi2 %.3g\n", ToString(result.verdict).c_str(),
                result.base.reduced_chi_square);
    EXPECT_EQ(result.selected.front(), "sensor_gain(acc1)") << result.summary;
    EXPECT_EQ(result.blame, Blame::kRecording);
  }
}

}  // namespace
}  // namespace beamid::solver
