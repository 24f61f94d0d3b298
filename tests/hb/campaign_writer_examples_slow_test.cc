// The paper's example campaign (examples/scenarios/paper_base.json), simulated
// in full: every recording passes signal's format validation, and the top
// level reaches the paper's ~5 g at the direct accelerometer.
#include <cmath>
#include <complex>
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "hb/campaign_writer.h"
#include "hb/scenario.h"
#include "hb/stepped_sine.h"
#include "signal/campaign.h"
#include "signal/recording.h"
#include "tests/support/temp_path.h"

namespace beamid::hb {
namespace {

TEST(CampaignWriterExamplesTest, PaperBaseCampaignValidatesAndReachesFiveG) {
  const std::filesystem::path directory = beamid::testing::UniqueTempPath("beamid_paper_base_slow_test");
  std::filesystem::remove_all(directory);
  const Scenario scenario = ReadScenario("examples/scenarios/paper_base.json");
  SteppedSineSimulation simulation(scenario);
  CampaignWriter writer(simulation, directory);
  int unsettled = 0;
  simulation.Run([&](const SimulatedStep& step) {
    writer.Write(step);
    unsettled += step.settled ? 0 : 1;
  });
  writer.Finish();
  EXPECT_EQ(unsettled, 0);
  EXPECT_EQ(writer.clipped_samples(), 0);

  const signal::Campaign campaign = signal::ReadCampaign(directory);
  ASSERT_EQ(static_cast<int>(campaign.steps.size()), scenario.NumSteps());
  for (const signal::Step& step : campaign.steps) EXPECT_NO_THROW(signal::ReadRecording(campaign, step)) << step.file;

  std::ifstream truth_file(directory / "truth.json");
  const nlohmann::json truth = nlohmann::json::parse(truth_file);
  double peak_high_g = 0.0;
  for (const auto& step : truth.at("steps")) {
    if (step.at("level") != "high") continue;
    const auto& h1 = step.at("channels").at("acc3").at("harmonics").at(0);
    peak_high_g = std::max(peak_high_g, std::hypot(h1.at(0).get<double>(), h1.at(1).get<double>()) / 9.80665);
  }
  EXPECT_GT(peak_high_g, 4.0);
  EXPECT_LT(peak_high_g, 6.0);
  std::filesystem::remove_all(directory);
}

}  // namespace
}  // namespace beamid::hb
