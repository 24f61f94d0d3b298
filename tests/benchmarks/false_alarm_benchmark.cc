// False alarms of the diagnosis where there is nothing to find: 50 noise
// realisations of one time-domain simulation of the paper's campaign whose
// physics is the base model (polynomial support, nominal beam, loss factor;
// 3 levels × 9 steps), diagnosed under each phasor weighting, and under
// `propagated` with the physics settled or exact (Physics below). Counters:
// - alarm_rate: a cause named or the misfit called unexplained, with the
//   95 % Wilson interval of the rate (alarm_low, alarm_high); a cause is
//   named by the likelihood-ratio test alone (no gate on the base misfit),
//   which states at most `significance` (1 %);
// - noise_drive_rate: realisations in which a force harmonic k ≥ 2 drives
//   the model (the simulator's force is a pure sine: any is noise; the test
//   of MakeFitData states 0.1 % per campaign);
// - base_reduced_chi2: the base fits' mean reduced χ².
// Each realisation that alarms is named on stderr with its verdict, base
// misfit, best candidate and the diagnosis's summary.
// Runs 4–5 s per realisation on 2 cores (219–263 s per weighting).
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>

#include <benchmark/benchmark.h>

#include "solver/diagnosis/diagnosis.h"
#include "tests/support/proof_diagnosis.h"
#include "tests/support/simulated_campaign.h"
#include "tests/support/wilson_interval.h"

namespace {

using namespace beamid;
// tests/support/, not GoogleTest's namespace of the same name.
namespace support = beamid::testing;

constexpr int kRealisations = 50;

bool NoiseDrivesTheModel(const solver::FitData& data) {
  for (const solver::FitStep& step : data.steps)
    for (Eigen::Index k = 2; k < step.force_N.size(); ++k)
      if (step.force_N[k] != 0.0) return true;
  return false;
}

// What is simulated beside the base model's support: the paper's campaign as
// it is (steps settled to 1e-5, the beam's loss factor integrated as the
// modal law), every step settled (SettleTightly), or settled and diagnosed
// with that law: the physics the diagnosed model holds exactly.
enum class Physics { kPaper, kSettled, kExact };

void BM_FalseAlarms(benchmark::State& state, solver::PhasorUncertainty weighting, Physics physics = Physics::kPaper) {
  nlohmann::json json = support::PaperSetUpScenario();
  if (physics != Physics::kPaper) support::SettleTightly(json);
  const solver::DiagnosisOptions options{.modal_loss_factor = physics == Physics::kExact};
  const hb::Scenario scenario = hb::ParseScenario(json.dump(), "false alarm benchmark scenario");
  const std::vector<hb::SimulatedStep> steps = support::SimulateSteps(scenario);
  const support::ExtractedCampaign written = support::WriteAndExtract(scenario, steps, 1, "beamid_false_alarm");
  int alarms = 0, noise_driven = 0;
  double chi2_sum = 0.0;
  for (auto _ : state) {
    for (int r = 0; r < kRealisations; ++r) {
      const signal::PhasorSet phasors = support::MeasureAgain(scenario, steps, written.campaign, 5000 + r);
      const support::ProofData data = support::MakeProofData(written.campaign, phasors, {.uncertainty = weighting});
      const solver::DiagnosisResult result = support::DiagnoseProofData(data, options);
      const bool alarm = result.verdict != solver::DiagnosisVerdict::kNoSignificantDiscrepancy;
      alarms += alarm;
      noise_driven += NoiseDrivesTheModel(data.fit);
      if (alarm)
        std::fprintf(stderr, "realisation %d: %s; base reduced chi2 %.3g; best %s (drop %.3gx, p %.2g)\n%s\n", r,
                     solver::ToString(result.verdict).c_str(), result.base.reduced_chi_square,
                     result.candidates.front().name.c_str(), result.candidates.front().residual_drop,
                     result.candidates.front().p_value, result.summary.c_str());
      chi2_sum += result.base.reduced_chi_square;
    }
  }
  std::filesystem::remove_all(written.folder);
  const support::RateInterval alarm = support::WilsonInterval(alarms, kRealisations),
                             driven = support::WilsonInterval(noise_driven, kRealisations);
  state.counters["alarm_rate"] = alarm.rate;
  state.counters["alarm_low"] = alarm.low;
  state.counters["alarm_high"] = alarm.high;
  state.counters["noise_drive_rate"] = driven.rate;
  state.counters["noise_drive_high"] = driven.high;
  state.counters["base_reduced_chi2"] = chi2_sum / kRealisations;
}

BENCHMARK_CAPTURE(BM_FalseAlarms, relative_floor, solver::PhasorUncertainty::kRelativeFloor)
    ->Iterations(1)->Unit(benchmark::kSecond);
BENCHMARK_CAPTURE(BM_FalseAlarms, propagated, solver::PhasorUncertainty::kPropagated)
    ->Iterations(1)->Unit(benchmark::kSecond);
BENCHMARK_CAPTURE(BM_FalseAlarms, propagated_settled, solver::PhasorUncertainty::kPropagated, Physics::kSettled)
    ->Iterations(1)->Unit(benchmark::kSecond);
BENCHMARK_CAPTURE(BM_FalseAlarms, propagated_exact, solver::PhasorUncertainty::kPropagated, Physics::kExact)
    ->Iterations(1)->Unit(benchmark::kSecond);

}  // namespace
