// The test guided while it runs against the uniform campaign, on the
// paper's set-up (examples/scenarios/paper_base.json) with the simulator's
// noise. The uniform campaign (3 levels × 33 steps, each settled by the
// simulator's rule to 1e-5 and recorded 0.5 s) is simulated and identified
// as `beamid identify` does; its rig time is the sum of its steps' settle and
// record times. Then `beamid watch` with the simulator as its rig (closed
// loop) runs until k1, k3 and c reach
//   - 1 % of their values (BM_GuidedToOnePercent), and
//   - the σ the uniform campaign gave them (BM_GuidedToUniformSigma), and
//     the same with the beam's damping fitted as the simulator's own law,
//     the modal loss factor (BM_GuidedToUniformSigmaModalLoss),
// or until it stops by itself; counters: its steps and rig time, the ratio
// to the uniform campaign's, each target's σ over its goal, the truth's
// distance in σ, and the update after each step (extract + refit + plan)
// in wall time, mean and largest.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <string>

#include <benchmark/benchmark.h>

#include "hb/campaign_writer.h"
#include "hb/scenario.h"
#include "hb/stepped_sine.h"
#include "solver/workflow/identify_campaign.h"
#include "solver/workflow/watch_campaign.h"

namespace {

using namespace beamid;
namespace fs = std::filesystem;

const std::map<std::string, double> kTruth{{"k1", 150.0}, {"k3", 3e5}, {"c", 0.05}};

fs::path Scenario() { return fs::path(BEAMID_SOURCE_DIR) / "examples/scenarios/paper_base.json"; }

struct Uniform {
  double rig_time_s = 0.0;
  int steps = 0;
  std::map<std::string, double> std;
};

const Uniform& UniformCampaign() {
  static const Uniform uniform = [] {
    const fs::path folder = fs::temp_directory_path() / "beamid_closed_loop_benchmark_uniform";
    fs::remove_all(folder);
    const hb::Scenario scenario = hb::ReadScenario(Scenario());
    hb::SteppedSineSimulation simulation(scenario);
    hb::CampaignWriter writer(simulation, folder);
    Uniform out;
    simulation.Run([&](const hb::SimulatedStep& step) {
      writer.Write(step);
      out.rig_time_s += step.settle_s + scenario.timing.record_s;
      ++out.steps;
    });
    writer.Finish();
    const fs::path result = fs::temp_directory_path() / "beamid_closed_loop_uniform.json";
    workflow::IdentifyRequest request{
        .campaign_folder = folder.string(), .damping_envelope = false, .output = result.string()};
    const workflow::IdentifyOutcome identified = workflow::IdentifyCampaign(request);
    for (const solver::ParameterEstimate& p : identified.Result().parameters) out.std[p.name] = p.std;
    fs::remove_all(folder);
    return out;
  }();
  return uniform;
}

void RunGuided(benchmark::State& state, bool to_uniform_sigma, bool modal_loss_factor = false) {
  const Uniform& uniform = UniformCampaign();
  for (auto _ : state) {
    const fs::path root = fs::temp_directory_path() / "beamid_closed_loop_benchmark_guided";
    fs::remove_all(root);
    fs::create_directories(root);
    workflow::WatchRequest request{.campaign_folder = (root / "campaign").string(),
                                   .plan_file = (root / "plan.json").string(),
                                   .virtual_rig = Scenario().string()};
    solver::PlannerOptions& planner = request.live.planner;
    planner.levels = {{"low", 1.0}, {"mid", 4.0}, {"high", 9.0}};
    planner.band_low_hz = 50.0;
    planner.band_high_hz = 58.0;
    planner.max_steps = 200;
    request.live.modal_loss_factor = modal_loss_factor;
    if (to_uniform_sigma)
      for (const auto& [name, truth] : kTruth) planner.target_std[name] = uniform.std.at(name);
    double update_sum = 0.0, update_max = 0.0;
    int updates = 0;
    const workflow::WatchOutcome outcome = workflow::WatchCampaign(request, {}, [&](const solver::LiveUpdate& u) {
      const double seconds = u.extract_s + u.fit_s + u.plan_s;
      update_sum += seconds;
      update_max = std::max(update_max, seconds);
      ++updates;
    });
    state.counters["uniform_rig_s"] = uniform.rig_time_s;
    state.counters["uniform_steps"] = uniform.steps;
    state.counters["guided_rig_s"] = outcome.rig_time_s;
    state.counters["guided_steps"] = outcome.rig_steps;
    state.counters["rig_time_ratio"] = outcome.rig_time_s / uniform.rig_time_s;
    bool reached = true;
    for (const solver::PlanParameter& p : outcome.plan.parameters) {
      if (!kTruth.contains(p.name)) continue;
      reached = reached && p.std <= p.target_std;
      state.counters[p.name + "_std_over_goal"] = p.std / p.target_std;
      state.counters[p.name + "_uniform_std"] = uniform.std.at(p.name);
      state.counters[p.name + "_z"] = (p.value - kTruth.at(p.name)) / p.std;
      // Inside the last plan's 95 % interval (model-form under E(1 + iη)).
      state.counters[p.name + "_in_interval"] = p.lower_95 <= kTruth.at(p.name) && kTruth.at(p.name) <= p.upper_95;
    }
    state.counters["targets_reached"] = reached;
    state.counters["within_noise"] = outcome.plan.reduced_chi_square <= 2.0;
    state.counters["reduced_chi_square"] = outcome.plan.reduced_chi_square;
    state.counters["update_mean_s"] = updates > 0 ? update_sum / updates : 0.0;
    state.counters["update_max_s"] = update_max;
    state.SetLabel(outcome.plan.done_reason);
    fs::remove_all(root);
  }
}

void BM_GuidedToOnePercent(benchmark::State& state) { RunGuided(state, false); }
void BM_GuidedToUniformSigma(benchmark::State& state) { RunGuided(state, true); }
void BM_GuidedToUniformSigmaModalLoss(benchmark::State& state) { RunGuided(state, true, true); }

BENCHMARK(BM_GuidedToOnePercent)->Unit(benchmark::kSecond)->Iterations(1);
BENCHMARK(BM_GuidedToUniformSigma)->Unit(benchmark::kSecond)->Iterations(1);
BENCHMARK(BM_GuidedToUniformSigmaModalLoss)->Unit(benchmark::kSecond)->Iterations(1);

}  // namespace
