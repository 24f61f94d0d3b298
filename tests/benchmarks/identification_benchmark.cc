// Identification benchmark: identification of 3 levels × 40 steps × 2 channels
// from one start (target < 2 s), the multistart with 32 starts on the
// machine's cores, and the plain nested approach on the same data (the
// ratio is reported as a counter). The campaign comes from the time-domain
// simulator (made once, ~10 s, before the timings).
#include <filesystem>

#include <benchmark/benchmark.h>

#include "hb/campaign_writer.h"
#include "hb/scenario.h"
#include "hb/stepped_sine.h"
#include "signal/campaign.h"
#include "signal/campaign_extractor.h"
#include "solver/estimation/identify.h"
#include "solver/estimation/nested_fit.h"

namespace {

using namespace beamid;

// settle_max_s 8: near resonance a step needs ~5 s to settle to 1e-5; cut at
// 4 s every step kept a transient that moved the fit by 2–4 σ
// (docs/simulator.md, "Accuracy seen by an identification").
const std::string kScenario = R"({
  "name": "benchmark: paper set-up, 3 levels x 40 steps",
  "beam": {"length_m": 0.6, "width_m": 0.04, "thickness_m": 0.005, "youngs_modulus_Pa": 2.1e11,
           "density_kg_m3": 7850, "loss_factor": 0.0002},
  "support": {"polynomial": {"k1_Nm_rad": 150, "k3_Nm_rad3": 3e5, "c_Nms_rad": 0.05}},
  "excitation": {"channel": "force", "position_m": 0.57},
  "sensors": [{"channel": "acc1", "position_m": 0.1}, {"channel": "acc2", "position_m": 0.3},
              {"channel": "acc3", "position_m": 0.57}],
  "levels": [{"label": "low", "force_amplitude_N": 1.0, "frequencies_Hz": {"start": 50, "stop": 59.75, "step": 0.25}},
             {"label": "mid", "force_amplitude_N": 4.0, "frequencies_Hz": {"start": 50, "stop": 59.75, "step": 0.25}},
             {"label": "high", "force_amplitude_N": 11.0, "frequencies_Hz": {"start": 50, "stop": 59.75, "step": 0.25}}],
  "timing": {"sample_rate_Hz": 5120, "settle_min_s": 0.2, "settle_max_s": 8.0, "transient_s": 0.05, "record_s": 0.5},
  "noise": {"seed": 11, "clock_offset_ppm": 25,
            "default": {"relative_rms": 0.003, "absolute": 0.005, "adc_bits": 24, "adc_range": 500}}
})";

const solver::FitData& Data() {
  static const solver::FitData data = [] {
    const auto folder = std::filesystem::temp_directory_path() / "beamid_identification_benchmark";
    std::filesystem::remove_all(folder);
    const hb::Scenario scenario = hb::ParseScenario(kScenario, "benchmark scenario");
    hb::SteppedSineSimulation simulation(scenario);
    hb::CampaignWriter writer(simulation, folder);
    simulation.Run([&](const hb::SimulatedStep& step) { writer.Write(step); });
    writer.Finish();
    const signal::Campaign campaign = signal::ReadCampaign(folder);
    const signal::PhasorSet phasors = signal::ExtractCampaign(campaign);
    solver::FitData fit = solver::MakeFitData(campaign, phasors, {.channels = {"acc1", "acc2"}});
    std::filesystem::remove_all(folder);
    return fit;
  }();
  return data;
}

void BM_IdentifyOneStart(benchmark::State& state) {
  const solver::FitData& data = Data();
  for (auto _ : state) {
    const auto result = solver::Identify(data, solver::PolynomialModel({.k1_Nm_rad = 100.0}), {});
    benchmark::DoNotOptimize(result.chi_square);
    state.counters["k1"] = result.parameters[0].value;
    state.counters["steps"] = static_cast<double>(data.steps.size());
  }
}
BENCHMARK(BM_IdentifyOneStart)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(3);

void BM_Identify32Starts(benchmark::State& state) {
  const solver::FitData& data = Data();
  solver::IdentifyOptions options;
  options.num_starts = 31;
  for (auto _ : state) {
    const auto result = solver::Identify(data, solver::PolynomialModel({.k1_Nm_rad = 100.0}), options);
    state.counters["starts_at_best"] = result.starts_at_best;
  }
}
BENCHMARK(BM_Identify32Starts)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(1);

void BM_NestedFitOneStart(benchmark::State& state) {
  const solver::FitData& data = Data();
  const auto structure = solver::PolynomialModel({.k1_Nm_rad = 100.0});
  // The same start as Identify's: the direct estimate.
  const auto direct = solver::EstimatePolynomialDirectly(
      solver::ReconstructSupport(data, {.beam = data.beam, .attachments = data.sensor_masses}));
  for (auto _ : state) {
    const auto result = solver::NestedFit(
        data, structure, {direct.k1_Nm_rad, direct.k2_Nm_rad2, direct.k3_Nm_rad3, std::max(direct.c_Nms_rad, 1e-5)});
    state.counters["k1"] = result.parameters[0];
    state.counters["step_solves"] = result.step_solves;
  }
}
BENCHMARK(BM_NestedFitOneStart)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(3);

}  // namespace
