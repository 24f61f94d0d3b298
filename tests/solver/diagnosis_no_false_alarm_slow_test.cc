// No false alarm: on campaigns whose physics IS the diagnosed model
// (polynomial support, nominal beam, every step settled, the beam's damping
// the simulator's own modal law and fitted as such), the diagnosis under
// the default weighting (`propagated`) names no cause. One noise-free
// simulation of the time-domain simulator, measured again with ten noise
// seeds: the first ten of false_alarm_benchmark's propagated_exact, which
// raised no alarm in 50. The positive control: the same recordings with
// acc1's gain off by 0.05 % (its phasors and their σ scaled, as a wrong
// calibration factor scales the record) are named (beside an equally good
// position error of acc1: these data cannot tell the two apart); a detector
// that always said "nothing" would pass the first half and fail this one.
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
// Within a factor 2.5 of what the diagnosis detects here: at 0.02 % the
// same three realisations read "nothing" twice and "unexplained" once
// (base reduced χ² 1.0–1.19); at 0.05 % all three are named (1.9–2.3).
constexpr double kControlGainError = 5e-4;

TEST(DiagnosisOnBasePhysics, RaisesNoFalseAlarmOverTenNoiseRealisations) {
  nlohmann::json json = testing::PaperSetUpScenario();
  testing::SettleTightly(json);
  const hb::Scenario scenario = hb::ParseScenario(json.dump(), "diagnosis_no_false_alarm scenario");
  const std::vector<hb::SimulatedStep> steps = testing::SimulateSteps(scenario);
  const testing::ExtractedCampaign written = testing::WriteAndExtract(scenario, steps, 1, "beamid_diagnosis_base");
  std::filesystem::remove_all(written.folder);
  const DiagnosisOptions exact{.modal_loss_factor = true};
  const FitDataOptions propagated{.uncertainty = PhasorUncertainty::kPropagated};
  int alarms = 0;
  std::vector<signal::PhasorSet> controls;
  for (int r = 0; r < kRealisations; ++r) {
    const signal::PhasorSet phasors = testing::MeasureAgain(scenario, steps, written.campaign, 5000 + r);
    const DiagnosisResult result =
        testing::DiagnoseProofData(testing::MakeProofData(written.campaign, phasors, propagated), exact);
    if (r < kControls) controls.push_back(phasors);
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

  for (signal::PhasorSet& phasors : controls) {
    for (signal::StepPhasors& step : phasors.steps)
      for (signal::ChannelPhasors& response : step.responses)
        if (response.channel == "acc1")
          for (signal::HarmonicPhasor& h : response.harmonics) {
            h.value *= 1.0 + kControlGainError;
            h.std_real *= 1.0 + kControlGainError;
            h.std_imag *= 1.0 + kControlGainError;
          }
    const DiagnosisResult result =
        testing::DiagnoseProofData(testing::MakeProofData(written.campaign, phasors, propagated), exact);
    std::printf("control: %s; base reduced chi2 %.3g\n", ToString(result.verdict).c_str(),
                result.base.reduced_chi_square);
    // Under these σ a gain this small and a position 30 µm off change acc1
    // alike; "indistinguishable", naming both, is the right answer too.
    EXPECT_NE(std::find(result.selected.begin(), result.selected.end(), "sensor_gain(acc1)"), result.selected.end())
        << result.summary;
    EXPECT_EQ(result.blame, Blame::kRecording);
  }
}

}  // namespace
}  // namespace beamid::solver
