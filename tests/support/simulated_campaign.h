// Test support: campaigns from the independent time-domain simulator
// (hb/stepped_sine), written in the campaign format to a temporary folder,
// read back and extracted (harmonics 1..5), with their truth: what the
// identification tests fit (never data from the model being fitted); and
// re-noised copies of one noise-free simulation (the simulation is the slow
// part, the noise is drawn when the campaign is written).
#pragma once

#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "hb/campaign_writer.h"
#include "hb/noise.h"
#include "hb/scenario.h"
#include "hb/stepped_sine.h"
#include "signal/campaign.h"
#include "signal/campaign_extractor.h"
#include "signal/phasor_estimator.h"
#include "solver/estimation/fit_data.h"
#include "tests/support/paper_scenario.h"
#include "tests/support/temp_path.h"

namespace beamid::testing {

struct SimulatedCampaign {
  std::filesystem::path folder;
  signal::Campaign campaign;
  signal::PhasorSet phasors;
  nlohmann::json truth;

  SimulatedCampaign(const std::string& scenario_json, const std::string& name) : folder(UniqueTempPath(name)) {
    std::filesystem::remove_all(folder);
    const hb::Scenario scenario = hb::ParseScenario(scenario_json, name + " scenario");
    hb::SteppedSineSimulation simulation(scenario);
    hb::CampaignWriter writer(simulation, folder);
    simulation.Run([&](const hb::SimulatedStep& step) { writer.Write(step); });
    writer.Finish();
    campaign = signal::ReadCampaign(folder);
    signal::ExtractOptions extract;
    extract.estimator.num_harmonics = 5;
    phasors = signal::ExtractCampaign(campaign, extract);
    std::ifstream truth_file(folder / "truth.json");
    truth = nlohmann::json::parse(truth_file);
  }
  ~SimulatedCampaign() { std::filesystem::remove_all(folder); }
  SimulatedCampaign(const SimulatedCampaign&) = delete;
  SimulatedCampaign& operator=(const SimulatedCampaign&) = delete;
};

struct ExtractedCampaign {
  std::filesystem::path folder;
  signal::Campaign campaign;
  signal::PhasorSet phasors;

  solver::FitData Fit(std::vector<std::string> channels, int harmonics = 3) const {
    return solver::MakeFitData(campaign, phasors, {.channels = std::move(channels), .num_fit_harmonics = harmonics});
  }
};

inline ExtractedCampaign ExtractFolder(const std::filesystem::path& folder) {
  ExtractedCampaign out{.folder = folder, .campaign = signal::ReadCampaign(folder), .phasors = {}};
  signal::ExtractOptions extract;
  extract.estimator.num_harmonics = 5;
  out.phasors = signal::ExtractCampaign(out.campaign, extract);
  return out;
}

// Simulated steps kept in memory, to write with any noise seed.
inline std::vector<hb::SimulatedStep> SimulateSteps(const hb::Scenario& scenario) {
  hb::SteppedSineSimulation simulation(scenario);
  std::vector<hb::SimulatedStep> steps;
  simulation.Run([&](const hb::SimulatedStep& step) { steps.push_back(step); });
  return steps;
}

// Simulates the scenario and writes its campaign (CSV files, campaign.json,
// truth.json, noise drawn from the scenario's seed) into `folder`; returns the
// noise-free steps, in the order simulated.
inline std::vector<hb::SimulatedStep> SimulateInto(const hb::Scenario& scenario, const std::filesystem::path& folder) {
  hb::SteppedSineSimulation simulation(scenario);
  std::vector<hb::SimulatedStep> steps;
  hb::CampaignWriter writer(simulation, folder);
  simulation.Run([&](const hb::SimulatedStep& step) {
    writer.Write(step);
    steps.push_back(step);
  });
  writer.Finish();
  return steps;
}

// Writes the steps with the scenario's noise drawn from `seed` and extracts them.
inline ExtractedCampaign WriteAndExtract(const hb::Scenario& scenario, const std::vector<hb::SimulatedStep>& steps,
                                         std::uint64_t seed, const std::string& name) {
  hb::Scenario noisy = scenario;
  noisy.seed = seed;
  const std::filesystem::path folder = UniqueTempPath(name);
  std::filesystem::remove_all(folder);
  const hb::SteppedSineSimulation simulation(noisy);  // not run: it carries the scenario to the writer
  hb::CampaignWriter writer(simulation, folder);
  for (const auto& step : steps) writer.Write(step);
  writer.Finish();
  return ExtractFolder(folder);
}

// One realisation of the measurement on the clean recordings, extracted as
// `beamid extract` does (the CSV's 9 significant digits aside).
inline signal::PhasorSet MeasureAgain(const hb::Scenario& scenario, const std::vector<hb::SimulatedStep>& steps,
                          const signal::Campaign& campaign, std::uint64_t seed) {
  hb::MeasurementNoise noise(seed);
  signal::PhasorSet set{.campaign = campaign.name, .num_harmonics = 5, .steps = {}};
  const std::vector<const signal::ChannelSpec*> channels = campaign.Channels();
  for (std::size_t i = 0; i < steps.size(); ++i) {
    signal::Recording recording{.file = steps[i].file, .channels = {}, .sample_rate_hz = scenario.timing.sample_rate_hz,
                                .start_time_s = 0.0, .samples = noise.Measure(scenario, steps[i].recording, nullptr)};
    for (std::size_t c = 0; c < channels.size(); ++c) {
      recording.channels.push_back(channels[c]->channel);
      recording.samples.col(static_cast<Eigen::Index>(c)) *= channels[c]->to_si_factor;
    }
    set.steps.push_back(signal::EstimateStepPhasors(recording, campaign, campaign.steps[i], {.num_harmonics = 5}));
  }
  return set;
}

// Every step settled until its fundamental changes by 1e-8 between windows
// (at most 40 s) instead of 1e-5. What the frequency step's ringing leaves
// at 1e-5 scatters the identified damping 1.3–1.4 times its σ under
// propagated σ (docs/identify.md, "Coverage, measured"); settled this far
// the recordings hold the model's physics alone. Diagnosed with the beam's
// damping as the modal loss factor (DiagnosisOptions::modal_loss_factor),
// the simulator's own law, the diagnosed model then holds the simulated
// physics exactly. (An undamped beam would not do: its higher modes'
// transients outlast settle_max_s, and every step of the paper set-up was
// cut at 40 s unsettled, k1 and k3 scattering 1.2–1.3 times their σ.)
inline void SettleTightly(nlohmann::json& scenario) {
  scenario["timing"]["settle_tolerance"] = 1e-8;
  scenario["timing"]["settle_max_s"] = 40.0;
}

// The paper's set-up with base physics (polynomial support), three levels
// (1, 4, 9 N) of nine steps around the resonance, realistic noise, each step
// settled to 1e-5 or cut at 8 s (tests/support/paper_scenario.h).
inline nlohmann::json PaperSetUpScenario() {
  return nlohmann::json::parse(PaperScenarioJson(
      "test: paper set-up, base physics",
      R"([{"label": "low", "force_amplitude_N": 1.0, "frequencies_Hz": {"start": 51, "stop": 57, "step": 0.75}},
          {"label": "mid", "force_amplitude_N": 4.0, "frequencies_Hz": {"start": 51, "stop": 57, "step": 0.75}},
          {"label": "high", "force_amplitude_N": 9.0, "frequencies_Hz": {"start": 51, "stop": 57, "step": 0.75}}])",
      11));
}

// The paper's example campaign (examples/scenarios/paper_base.json: 1, 4
// and 9 N) with 15 steps per level instead of 33, over the resonance. Its
// noise is that of a real test of this beam, not tuned for any check:
// - accelerometers: 0.005 m/s² rms broadband (0.5 mg over the 2.56 kHz band,
//   ≈ 10 µg/√Hz: a general-purpose ICP accelerometer on a 24-bit DAQ) plus
//   0.3 % of the channel's rms for the signal-proportional errors of a real
//   chain (gain ripple, cable and mounting motion, shaker-table noise). At
//   1 N the responses are 0.8–30 m/s², so the floor is 45–75 dB below them;
//   the 0.3 % part keeps every SNR near 50 dB;
// - force transducer: 0.002 N rms plus 0.2 % of its rms;
// - 24-bit ADCs over ±500 m/s² and ±50 N; generator clock 25 ppm off.
// LeanExample takes any examples/scenarios/ file the same way (15 steps
// per level, no hidden positions). Read from the repository's root (the
// tests' working directory).
inline nlohmann::json LeanExample(const std::string& file_name) {
  std::ifstream file("examples/scenarios/" + file_name);
  if (!file) throw std::runtime_error("examples/scenarios/" + file_name + ": run from the repository's root");
  nlohmann::json scenario = nlohmann::json::parse(file);
  for (auto& level : scenario["levels"]) level["frequencies_Hz"] = {{"start", 51.0}, {"stop", 57.3}, {"step", 0.45}};
  scenario.erase("hidden_positions_m");
  return scenario;
}

inline hb::Scenario LeanPaperBase() {
  return hb::ParseScenario(LeanExample("paper_base.json").dump(), "paper_base.json, 15 steps per level");
}

// A Jenkins element (a spring in series with a Coulomb slider) beside the
// polynomial support, whose k1 becomes `k1_Nm_rad`, with the simulator's step
// and settling of examples/scenarios/paper_friction.json: a slipping support
// settles slowly, so the steps settle to 5e-4 (1e-5 would take minutes).
inline void AddSupportFriction(nlohmann::json& scenario, double k1_Nm_rad, double stiffness_Nm_rad,
                               double slip_moment_Nm) {
  scenario["support"]["polynomial"]["k1_Nm_rad"] = k1_Nm_rad;
  scenario["support"]["jenkins"] = {{"stiffness_Nm_rad", stiffness_Nm_rad}, {"slip_moment_Nm", slip_moment_Nm}};
  scenario["timing"]["max_time_step_s"] = 9.765625e-06;
  scenario["timing"]["settle_min_s"] = 1.0;
  scenario["timing"]["settle_tolerance"] = 5e-4;
}

inline ExtractedCampaign SimulateCampaign(const nlohmann::json& scenario_json, const std::string& name) {
  const hb::Scenario scenario = hb::ParseScenario(scenario_json.dump(), name);
  return WriteAndExtract(scenario, SimulateSteps(scenario), scenario.seed, name);
}

}  // namespace beamid::testing
