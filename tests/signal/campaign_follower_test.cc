// The campaign follower against an acquisition that writes slowly, in
// pieces, out of order and once faultily: every step is handed out once,
// only when complete, and a faulty one again only after it was rewritten.
// The recordings are the time-domain simulator's (hb/stepped_sine.h).
#include "signal/campaign_follower.h"

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "hb/errors.h"
#include "hb/scenario.h"
#include "tests/support/file_bytes.h"
#include "tests/support/paper_scenario.h"
#include "tests/support/simulated_campaign.h"
#include "tests/support/temp_path.h"

namespace beamid::signal {
namespace {

namespace fs = std::filesystem;

void WriteFile(const fs::path& path, const std::string& text) {
  fs::create_directories(path.parent_path());
  beamid::testing::WriteFile(path, text);
}

class CampaignFollowerTest : public ::testing::Test {
 protected:
  void SetUp() override {
    source_ = beamid::testing::UniqueTempPath("beamid_follower_source");
    live_ = beamid::testing::UniqueTempPath("beamid_follower_live");
    fs::remove_all(source_);
    fs::remove_all(live_);
    // Three steps far below resonance: they settle at once.
    const hb::Scenario scenario = hb::ParseScenario(
        beamid::testing::PaperScenarioJson(
            "follower", R"([{"label": "low", "force_amplitude_N": 1, "frequencies_Hz": [40, 41, 42]}])", 7),
        "follower.json");
    beamid::testing::SimulateInto(scenario, source_);
    fs::create_directories(live_);
  }
  void TearDown() override {
    fs::remove_all(source_);
    fs::remove_all(live_);
  }
  void CopyStep(const std::string& file) { WriteFile(live_ / file, beamid::testing::ReadFile(source_ / file)); }

  fs::path source_, live_;
};

std::vector<std::string> Files(const std::vector<FollowedStep>& steps) {
  std::vector<std::string> out;
  for (const FollowedStep& step : steps) out.push_back(step.step.file);
  return out;
}

TEST_F(CampaignFollowerTest, HandsOutEachStepOnceWhenCompleteInTheOrderTheyComplete) {
  CampaignFollower follower(live_, {.stable_s = 1.0});
  EXPECT_TRUE(follower.Look(0.0).empty()) << "no campaign.json yet";
  WriteFile(live_ / "campaign.json", beamid::testing::ReadFile(source_ / "campaign.json"));  // lists all three steps
  // The third step arrives first, whole; the first in two pieces.
  CopyStep("low/step_002.csv");
  const std::string first = beamid::testing::ReadFile(source_ / "low/step_000.csv");
  WriteFile(live_ / "low/step_000.csv", first.substr(0, first.size() / 2));
  EXPECT_TRUE(follower.Look(1.0).empty()) << "a file seen once is not known to be complete";
  EXPECT_EQ(follower.waiting(), 3);
  // 0.5 s later: nothing is stable for 1 s yet.
  EXPECT_TRUE(follower.Look(1.5).empty());
  WriteFile(live_ / "low/step_000.csv", first);  // the rest arrives
  std::vector<FollowedStep> got = follower.Look(2.2);
  ASSERT_EQ(Files(got), std::vector<std::string>{"low/step_002.csv"});
  EXPECT_EQ(got[0].index, 2);
  EXPECT_EQ(got[0].status, FollowedStatus::kComplete);
  EXPECT_FALSE(got[0].again);
  EXPECT_GT(got[0].recording.NumSamples(), 1000);
  EXPECT_TRUE(follower.Look(2.5).empty()) << "step_000 changed at 2.2 s and is not yet stable";
  got = follower.Look(3.3);
  ASSERT_EQ(Files(got), std::vector<std::string>{"low/step_000.csv"});
  EXPECT_EQ(got[0].status, FollowedStatus::kComplete);
  // The whole file was read, not the half seen first.
  const Campaign whole = ReadCampaign(source_);
  EXPECT_EQ(got[0].recording.NumSamples(), ReadRecording(whole, whole.steps[0]).NumSamples());
  CopyStep("low/step_001.csv");
  EXPECT_TRUE(follower.Look(4.0).empty());
  got = follower.Look(5.0);
  ASSERT_EQ(Files(got), std::vector<std::string>{"low/step_001.csv"});
  EXPECT_EQ(follower.waiting(), 0);
  for (double t = 6.0; t < 10.0; t += 1.0) EXPECT_TRUE(follower.Look(t).empty()) << "nothing is handed out twice";
}

TEST_F(CampaignFollowerTest, AFaultyRecordingIsHandedOutOnceAndAgainOnlyWhenRewritten) {
  CampaignFollower follower(live_, {.stable_s = 0.5});
  WriteFile(live_ / "campaign.json", beamid::testing::ReadFile(source_ / "campaign.json"));
  // Cut after its header and a few rows: too short for any analysis.
  const std::string whole = beamid::testing::ReadFile(source_ / "low/step_001.csv");
  std::size_t cut = 0;
  for (int line = 0; line < 12; ++line) cut = whole.find('\n', cut) + 1;
  WriteFile(live_ / "low/step_001.csv", whole.substr(0, cut));
  EXPECT_TRUE(follower.Look(0.0).empty());
  std::vector<FollowedStep> got = follower.Look(1.0);
  ASSERT_EQ(got.size(), 1u);
  EXPECT_EQ(got[0].status, FollowedStatus::kFaulty);
  EXPECT_NE(got[0].error.find("step_001.csv"), std::string::npos) << got[0].error;
  EXPECT_TRUE(follower.Look(2.0).empty()) << "a faulty file is not read again while unchanged";
  EXPECT_EQ(follower.waiting(), 2) << "the two steps listed whose files are not there";
  CopyStep("low/step_001.csv");  // measured again
  EXPECT_TRUE(follower.Look(3.0).empty());
  got = follower.Look(4.0);
  ASSERT_EQ(got.size(), 1u);
  EXPECT_EQ(got[0].status, FollowedStatus::kComplete);
  EXPECT_TRUE(got[0].again);
}

TEST_F(CampaignFollowerTest, RefusesAStepOutsideTheFolderAndACampaignJsonThatStaysInvalid) {
  {
    CampaignFollower follower(live_, {.stable_s = 0.5, .invalid_looks = 3});
    WriteFile(live_ / "campaign.json", "{\"format\": ");  // half written
    EXPECT_TRUE(follower.Look(0.0).empty());
    EXPECT_TRUE(follower.Look(1.0).empty());
    EXPECT_THROW(follower.Look(2.0), InputError) << "invalid three looks in a row";
  }
  {
    std::string text = beamid::testing::ReadFile(source_ / "campaign.json");
    const std::string file = "\"low/step_000.csv\"";
    text.replace(text.find(file), file.size(), "\"../../etc/passwd\"");
    WriteFile(live_ / "campaign.json", text);
    CampaignFollower follower(live_, {.stable_s = 0.5});
    try {
      follower.Look(0.0);
      FAIL() << "a step outside the folder was accepted";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("outside the campaign folder"), std::string::npos) << e.what();
    }
  }
}

}  // namespace
}  // namespace beamid::signal
