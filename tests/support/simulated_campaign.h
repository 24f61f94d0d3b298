// A campaign simulated once per test binary by the independent time-domain
// simulator (hb/stepped_sine), written in the campaign format, read back and
// extracted (harmonics 1..5), with its truth file: what the identification
// tests fit (never data from the model being fitted).
#pragma once

#include <filesystem>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "hb/campaign_writer.h"
#include "hb/scenario.h"
#include "hb/stepped_sine.h"
#include "signal/campaign.h"
#include "signal/campaign_extractor.h"
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

}  // namespace beamid::testing
