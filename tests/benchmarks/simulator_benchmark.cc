// Speed of the time-domain simulator (the target: the three-level
// example campaign in under 30 s on one core) and of one integration step.
#include <cmath>
#include <filesystem>

#include <benchmark/benchmark.h>

#include "hb/campaign_writer.h"
#include "hb/scenario.h"
#include "hb/stepped_sine.h"
#include "hb/time_simulator.h"

namespace beamid::hb {
namespace {

std::filesystem::path SourceRoot() { return std::filesystem::path(__FILE__).parent_path().parent_path().parent_path(); }

// The whole example campaign, written to disk (counters: steps, MB on disk).
void BM_SimulateExampleCampaign(benchmark::State& state, const char* scenario_file) {
  const Scenario scenario = ReadScenario(SourceRoot() / "examples/scenarios" / scenario_file);
  const std::filesystem::path directory = std::filesystem::temp_directory_path() / "beamid_simulator_benchmark";
  double megabytes = 0.0;
  for (auto _ : state) {
    std::filesystem::remove_all(directory);
    SteppedSineSimulation simulation(scenario);
    CampaignWriter writer(simulation, directory);
    simulation.Run([&](const SimulatedStep& step) { writer.Write(step); });
    writer.Finish();
    megabytes = static_cast<double>(writer.bytes_written()) / 1e6;
  }
  std::filesystem::remove_all(directory);
  state.counters["steps"] = scenario.NumSteps();
  state.counters["MB_on_disk"] = megabytes;
}
BENCHMARK_CAPTURE(BM_SimulateExampleCampaign, paper_base, "paper_base.json")->Unit(benchmark::kSecond)->Iterations(1);
BENCHMARK_CAPTURE(BM_SimulateExampleCampaign, paper_friction, "paper_friction.json")
    ->Unit(benchmark::kSecond)
    ->Iterations(1);

// One time step with the scalar Newton on the support (per step: all modes
// updated, the law evaluated until convergence).
void BM_TimeStep(benchmark::State& state, bool with_friction) {
  TimeSimulatorModel model;
  model.beam.loss_factor = 0.004;
  model.output_positions_m = {0.1, 0.3, 0.57};
  CompositeSupportLaw law;
  law.Add(std::make_unique<PolynomialSupportLaw>(PolynomialSupportLaw::Coefficients{150.0, 0.0, 3e5, 0.05}));
  if (with_friction) law.Add(std::make_unique<JenkinsSupportLaw>(JenkinsSupportLaw::Parameters_{50.0, 0.15}));
  TimeSimulator sim(model, law);
  const double omega_dt = 2 * 3.141592653589793 * 54.0 * sim.time_step_s();
  long n = 0;
  for (auto _ : state) sim.Advance(11.0 * std::cos(omega_dt * static_cast<double>(++n)));
  benchmark::DoNotOptimize(sim.SupportRotation_rad());
  state.counters["modes"] = static_cast<double>(sim.modal_frequencies_rad_s().size());
}
BENCHMARK_CAPTURE(BM_TimeStep, polynomial, false);
BENCHMARK_CAPTURE(BM_TimeStep, polynomial_and_jenkins, true);

}  // namespace
}  // namespace beamid::hb
