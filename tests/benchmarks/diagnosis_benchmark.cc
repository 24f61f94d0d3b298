// Diagnosis benchmarks. First, a full diagnosis (base fit, misfit location, every
// candidate refitted in worker processes, selection, final model and
// response curves) of a 3-level campaign with concealed friction, 3 levels ×
// 13 steps × 2 fitted channels plus a held-out one (target < 30 s on 2
// cores). The campaign comes from the time-domain simulator (made once,
// before the timings; it is examples/concealed_friction/scenario.json).
// Then the same on the example campaigns of an incomplete model,
// 3 levels × 33 steps (examples/scenarios/paper_*.json: a modulus error,
// masses at the instruments, friction and a compliant clamp, Rayleigh beam
// damping, and the base physics), each simulated once before its timing.
// Last, faults of the recording (below).
#include <chrono>
#include <filesystem>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>

#include "hb/campaign_writer.h"
#include "hb/scenario.h"
#include "hb/stepped_sine.h"
#include "signal/campaign.h"
#include "signal/campaign_extractor.h"
#include "solver/diagnosis/diagnosis.h"
#include "solver/estimation/identify.h"
#include "solver/estimation/robust_fit.h"

namespace {

using namespace beamid;

struct Data {
  solver::FitData fit, validation, located;
};

Data Simulate(const std::string& scenario_file) {
    const auto folder = std::filesystem::temp_directory_path() / "beamid_diagnosis_benchmark";
    std::filesystem::remove_all(folder);
    const hb::Scenario scenario = hb::ReadScenario(std::filesystem::path(BEAMID_SOURCE_DIR) / scenario_file);
    hb::SteppedSineSimulation simulation(scenario);
    hb::CampaignWriter writer(simulation, folder);
    simulation.Run([&](const hb::SimulatedStep& step) { writer.Write(step); });
    writer.Finish();
    const signal::Campaign campaign = signal::ReadCampaign(folder);
    const signal::PhasorSet phasors = signal::ExtractCampaign(campaign);
    Data d{solver::MakeFitData(campaign, phasors, {.channels = {"acc1", "acc2"}}),
           solver::MakeFitData(campaign, phasors, {.channels = {"acc3"}}),
           solver::MakeFitData(campaign, phasors, {.channels = {"acc1", "acc2"}, .num_fit_harmonics = 5})};
    std::filesystem::remove_all(folder);
    return d;
}

const Data& Campaign() {
  static const Data data = Simulate("examples/concealed_friction/scenario.json");
  return data;
}

void BM_DiagnoseThreeLevels(benchmark::State& state) {
  const Data& data = Campaign();
  solver::DiagnosisOptions options;
  options.num_workers = static_cast<int>(state.range(0));
  for (auto _ : state) {
    const auto result = solver::Diagnose(data.fit, data.validation, data.located, options);
    state.counters["steps"] = static_cast<double>(data.fit.steps.size());
    state.counters["named_friction"] = result.selected.front() == "support_friction" ? 1 : 0;
    state.counters["residual_drop"] = result.base.chi_square / result.final_fit.chi_square;
  }
}
// 0: one worker per core; 1: every refit in turn, in this process.
BENCHMARK(BM_DiagnoseThreeLevels)->Arg(0)->Arg(1)->Unit(benchmark::kSecond)->UseRealTime()->Iterations(1);

}  // namespace

const std::vector<std::string> kIncompleteModels = {
    "examples/scenarios/paper_modulus_error.json", "examples/scenarios/paper_instrument_masses.json",
    "examples/scenarios/paper_friction_and_clamp.json", "examples/scenarios/paper_rayleigh_damping.json",
    "examples/scenarios/paper_base.json"};

void BM_DiagnoseIncompleteModel(benchmark::State& state) {
  const std::string& file = kIncompleteModels.at(static_cast<std::size_t>(state.range(0)));
  const Data data = Simulate(file);
  state.SetLabel(file.substr(file.rfind('/') + 1) + ": named ...");
  for (auto _ : state) {
    const auto result = solver::Diagnose(data.fit, data.validation, data.located, {});
    std::string named;
    for (const auto& s : result.selected) named += (named.empty() ? "" : " + ") + s;
    state.SetLabel(file.substr(file.rfind('/') + 1) + ": " + solver::ToString(result.verdict) + ": " + named);
    state.counters["steps"] = static_cast<double>(data.fit.steps.size());
    state.counters["chi2_base"] = result.base.chi_square;
    state.counters["chi2_final"] = result.final_fit.chi_square;
    state.counters["held_out_h1_base_pct"] = 100.0 * result.base.held_out_h1_relative_error;
    state.counters["held_out_h1_final_pct"] = 100.0 * result.final_fit.held_out_h1_relative_error;
  }
}
BENCHMARK(BM_DiagnoseIncompleteModel)->DenseRange(0, 4)->Unit(benchmark::kSecond)->UseRealTime()->Iterations(1);

// Faults of the recording: identify (ordinary fit, then the robust fit) and diagnose on the
// example campaigns with a fault of the recording, beside a physics one
// (friction) and the clean base. Counters: χ² of the base and of the named
// model, and k1, k3, c of the named model (the robust fit's when nothing is
// named) in standard uncertainties from the truth.
const std::vector<std::string> kRecordingFaults = {
    "examples/scenarios/paper_unsettled_step.json", "examples/scenarios/paper_sensor_gain.json",
    "examples/scenarios/paper_sensor_position.json", "examples/scenarios/paper_sensor_delay.json",
    "examples/scenarios/paper_clock_error.json",     "examples/scenarios/paper_friction.json",
    "examples/scenarios/paper_base.json"};

void BM_DiagnoseRecordingFault(benchmark::State& state) {
  const std::string& file = kRecordingFaults.at(static_cast<std::size_t>(state.range(0)));
  const Data data = Simulate(file);
  const hb::Scenario scenario = hb::ReadScenario(std::filesystem::path(BEAMID_SOURCE_DIR) / file);
  solver::ModelStructure structure = solver::PolynomialModel({.k1_Nm_rad = 100.0});
  structure.linear.push_back(solver::LossFactor(1e-4));
  for (auto _ : state) {
    const auto started = std::chrono::steady_clock::now();
    const solver::IdentifyResult ordinary = solver::Identify(data.fit, structure, {});
    const solver::RobustFitResult robust = solver::RobustRefit(data.fit, structure, ordinary, {});
    const double identify_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    const auto result = solver::Diagnose(data.fit, data.validation, data.located, {});
    std::string named;
    for (const auto& s : result.selected) named += (named.empty() ? "" : " + ") + s;
    state.SetLabel(file.substr(file.rfind('/') + 1) + ": " + solver::ToString(result.verdict) + ": " + named +
                   (result.blame == solver::Blame::kNone ? "" : " (" + solver::ToString(result.blame) + ")"));
    state.counters["identify_s"] = identify_s;
    state.counters["diagnose_s"] = result.seconds;
    state.counters["chi2_base"] = result.base.chi_square;
    state.counters["chi2_final"] = result.final_fit.chi_square;
    state.counters["chi2_robust"] = robust.fit.chi_square;
    state.counters["left_out"] = robust.applied ? static_cast<double>(robust.outliers.size()) : 0.0;
    const auto& parameters = result.selected.front() == "none" ? robust.fit.parameters : result.final_fit.parameters;
    const std::pair<const char*, double> truths[] = {{"k1", scenario.polynomial.k1_Nm_rad},
                                                     {"k3", scenario.polynomial.k3_Nm_rad3},
                                                     {"c", scenario.polynomial.c_Nms_rad}};
    for (const auto& [name, truth] : truths)
      for (const auto& p : parameters)
        if (p.name == name) state.counters[std::string(name) + "_sigma_from_truth"] = (p.value - truth) / p.std;
  }
}
BENCHMARK(BM_DiagnoseRecordingFault)->DenseRange(0, 6)->Unit(benchmark::kSecond)->UseRealTime()->Iterations(1);
