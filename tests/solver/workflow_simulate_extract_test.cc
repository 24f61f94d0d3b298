// The simulate and extract workflows called directly, without the program:
// a 3-step scenario simulated once for the suite is written where asked, each
// step told as it is written; its extraction holds the same phasors as a
// direct signal::ExtractCampaign and is what was written; a bad request is
// refused with an InputError naming the field before any work.
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "signal/campaign.h"
#include "signal/campaign_extractor.h"
#include "signal/phasor_set_io.h"
#include "solver/workflow/extract_campaign.h"
#include "solver/workflow/simulate_campaign.h"
#include "tests/support/expect_refused.h"
#include "tests/support/file_bytes.h"
#include "tests/support/paper_scenario.h"
#include "tests/support/temp_path.h"

namespace {

namespace fs = std::filesystem;
using beamid::testing::InputErrorOf;
using beamid::testing::ReadFile;
using ::testing::HasSubstr;
namespace workflow = beamid::workflow;

class SimulateAndExtract : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    root_ = beamid::testing::UniqueTempPath("beamid_simulate_workflow");
    fs::remove_all(root_);
    fs::create_directories(root_);
    beamid::testing::WriteFile(root_ / "scenario.json", beamid::testing::PaperScenarioJson("workflow", R"([
      {"label": "low", "force_amplitude_N": 0.5, "frequencies_Hz": {"start": 53.6, "stop": 54.6, "step": 0.5}}])", 3));
    outcome_ = workflow::SimulateCampaign(
        {.scenario = (root_ / "scenario.json").string(), .output = (root_ / "campaign").string()},
        {.begin = [](const std::string& task) { tasks_.push_back(task); }},
        [](const beamid::hb::SimulatedStep& step, int total) {
          steps_told_.push_back(std::to_string(step.index + 1) + "/" + std::to_string(total));
        });
  }
  static void TearDownTestSuite() { fs::remove_all(root_); }

  static inline fs::path root_;
  static inline workflow::SimulateOutcome outcome_;
  static inline std::vector<std::string> tasks_, steps_told_;
};

TEST_F(SimulateAndExtract, TheSimulationWritesTheCampaignAndTellsEachStep) {
  EXPECT_EQ(tasks_, std::vector<std::string>{"simulate"});
  EXPECT_EQ(steps_told_, (std::vector<std::string>{"1/3", "2/3", "3/3"}));
  EXPECT_EQ(outcome_.num_steps, 3);
  EXPECT_EQ(outcome_.unsettled_steps, 0);
  EXPECT_EQ(outcome_.clipped_samples, 0);
  EXPECT_GT(outcome_.bytes_written, 0u);
  const beamid::signal::Campaign campaign = beamid::signal::ReadCampaign(root_ / "campaign");
  EXPECT_EQ(campaign.steps.size(), 3u);
  EXPECT_TRUE(fs::exists(root_ / "campaign" / "truth.json"));
  // A campaign is never replaced without overwrite (bad input: the
  // writer's std::invalid_argument, exit 2 in the program).
  try {
    workflow::SimulateCampaign({.scenario = (root_ / "scenario.json").string(), .output = (root_ / "campaign").string()});
    ADD_FAILURE() << "replaced a campaign";
  } catch (const std::invalid_argument& e) {
    EXPECT_THAT(e.what(), HasSubstr("--overwrite"));
  }
}

TEST_F(SimulateAndExtract, TheExtractionIsADirectExtractionAndIsWritten) {
  const workflow::ExtractRequest request{.campaign_folder = (root_ / "campaign").string(),
                                         .harmonics = 3,
                                         .output = (root_ / "phasors.json").string(),
                                         .csv_output = (root_ / "phasors.csv").string()};
  const workflow::ExtractOutcome outcome = workflow::ExtractCampaign(request);
  beamid::signal::ExtractOptions options;
  options.estimator.num_harmonics = 3;
  const beamid::signal::PhasorSet direct =
      beamid::signal::ExtractCampaign(beamid::signal::ReadCampaign(root_ / "campaign"), options);
  EXPECT_EQ(beamid::signal::PhasorSetToJson(outcome.phasors), beamid::signal::PhasorSetToJson(direct));
  EXPECT_EQ(outcome.num_sensors, 3u);
  EXPECT_EQ(ReadFile(request.output), beamid::signal::PhasorSetToJson(direct));
  EXPECT_EQ(ReadFile(request.csv_output), beamid::signal::PhasorSetToCsv(direct));
}

TEST_F(SimulateAndExtract, ABadExtractRequestIsRefusedNamingTheField) {
  workflow::ExtractRequest request{.campaign_folder = (root_ / "campaign").string(),
                                   .harmonics = 0,
                                   .output = (root_ / "refused.json").string()};
  EXPECT_THAT(InputErrorOf([&] { workflow::ExtractCampaign(request); }), HasSubstr("-H/--harmonics"));
  request.harmonics = 3;
  request.threads = -1;
  EXPECT_THAT(InputErrorOf([&] { request.Validate(); }), AllOf(HasSubstr("--threads"), HasSubstr("must be")));
  request.threads = 0;
  request.output = (root_ / "campaign" / "phasors.json").string();  // inside the campaign it reads
  EXPECT_THAT(InputErrorOf([&] { request.Validate(); }), HasSubstr("-o"));
  request.output = (root_ / "refused.json").string();
  request.campaign_folder = (root_ / "no_such_campaign").string();
  EXPECT_THAT(InputErrorOf([&] { workflow::ExtractCampaign(request); }), HasSubstr(request.campaign_folder));
  EXPECT_FALSE(fs::exists(request.output));
}

}  // namespace
