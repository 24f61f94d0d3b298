// The campaign's content hash (signal/campaign_hash.h): it changes with any
// byte of campaign.json or of a recording, and with bytes moved from one
// recording to the next, not with the folder the campaign sits in; a file's
// own hash is what sha256sum prints. And ReadCampaign's warning of a
// recording that is a byte copy of another step's.
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "signal/campaign.h"
#include "signal/campaign_hash.h"
#include "signal/campaign_identity.h"
#include "signal/input_error.h"
#include "tests/support/temp_path.h"

namespace beamid::signal {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

void Write(const fs::path& path, const std::string& bytes) {
  fs::create_directories(path.parent_path());
  std::ofstream(path, std::ios::binary) << bytes;
}

const std::vector<std::string> kSteps = {"low/step_000.csv", "low/step_001.csv"};

class CampaignHashTest : public ::testing::Test {
 protected:
  void SetUp() override {
    folder_ = testing::UniqueTempPath("campaign_hash");
    fs::remove_all(folder_);
    Write(folder_ / "campaign.json", "{\"name\": \"hash test\"}\n");
    Write(folder_ / kSteps[0], "time_s,force\n0,1\n");
    Write(folder_ / kSteps[1], "time_s,force\n0,2\n");
    original_ = HashCampaign(folder_, kSteps).sha256;
  }
  void TearDown() override { fs::remove_all(folder_); }

  std::string Hash() const { return HashCampaign(folder_, kSteps).sha256; }

  fs::path folder_;
  std::string original_;
};

TEST_F(CampaignHashTest, IsSha256HexAndTheSameForTheSameBytes) {
  EXPECT_EQ(original_.size(), 64u);
  EXPECT_EQ(original_.find_first_not_of("0123456789abcdef"), std::string::npos) << original_;
  EXPECT_EQ(Hash(), original_);
}

TEST_F(CampaignHashTest, ChangesWithAnyByteOfCampaignJson) {
  Write(folder_ / "campaign.json", "{\"name\": \"hash tesT\"}\n");
  EXPECT_NE(Hash(), original_);
  Write(folder_ / "campaign.json", "{\"name\": \"hash test\"} \n");
  EXPECT_NE(Hash(), original_);
}

TEST_F(CampaignHashTest, ChangesWithAnyByteOfARecording) {
  Write(folder_ / kSteps[1], "time_s,force\n0,3\n");
  EXPECT_NE(Hash(), original_);
  Write(folder_ / kSteps[1], "time_s,force\n0,2\n");
  EXPECT_EQ(Hash(), original_);
  Write(folder_ / kSteps[0], "time_s,forcE\n0,1\n");
  EXPECT_NE(Hash(), original_);
}

// The concatenation of the two recordings is the same; where it is split is not.
TEST_F(CampaignHashTest, ChangesWhenBytesMoveFromOneRecordingToTheNext) {
  Write(folder_ / kSteps[0], "time_s,force\n0,1\nt");
  Write(folder_ / kSteps[1], "ime_s,force\n0,2\n");
  EXPECT_NE(Hash(), original_);
}

// Two steps in the other order are another campaign (each step's frequency
// and level would belong to the other recording).
TEST_F(CampaignHashTest, ChangesWithTheStepOrderAndAFileName) {
  EXPECT_NE(HashCampaign(folder_, {kSteps[1], kSteps[0]}).sha256, original_);
  fs::rename(folder_ / kSteps[1], folder_ / "low/step_002.csv");
  EXPECT_NE(HashCampaign(folder_, {kSteps[0], "low/step_002.csv"}).sha256, original_);
}

TEST_F(CampaignHashTest, DoesNotChangeWhenTheCampaignIsCopiedElsewhere) {
  const fs::path copy = testing::UniqueTempPath("campaign_hash_copy") / "elsewhere";
  fs::remove_all(copy.parent_path());
  fs::create_directories(copy);
  fs::copy(folder_, copy, fs::copy_options::recursive);
  EXPECT_EQ(HashCampaign(copy, kSteps).sha256, original_);
  fs::remove_all(copy.parent_path());
}

TEST_F(CampaignHashTest, AFileHashIsWhatSha256sumPrints) {
  // The standard test vectors (FIPS 180-2): "abc" and the empty message.
  Write(folder_ / "abc.txt", "abc");
  EXPECT_EQ(FileSha256(folder_ / "abc.txt"), "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
  Write(folder_ / "empty.txt", "");
  EXPECT_EQ(FileSha256(folder_ / "empty.txt"), "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
  // And a file larger than one read buffer, against the tool itself.
  std::string large;
  for (int i = 0; i < 100000; ++i) large += std::to_string(i) + ",";
  Write(folder_ / "large.csv", large);
  const fs::path printed = folder_ / "sha256sum.txt";
  ASSERT_EQ(std::system(("sha256sum '" + (folder_ / "large.csv").string() + "' > '" + printed.string() + "'").c_str()),
            0);
  std::ifstream in(printed);
  std::string expected;
  in >> expected;
  EXPECT_EQ(FileSha256(folder_ / "large.csv"), expected);
  EXPECT_EQ(HashCampaign(folder_, {"large.csv"}).step_sha256, std::vector<std::string>{expected});
}

TEST_F(CampaignHashTest, AMissingFileIsAnInputErrorNamingIt) {
  try {
    HashCampaign(folder_, {kSteps[0], "low/missing.csv"});
    FAIL();
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("missing.csv"));
  }
}

std::string CampaignJson() {
  return R"({
  "format": "stepped-sine-campaign/1",
  "name": "duplicate test",
  "beam": {"length_m": 0.6, "width_m": 0.04, "thickness_m": 0.005, "youngs_modulus_Pa": 2.1e11, "density_kg_m3": 7850},
  "excitation": {"channel": "force", "position_m": 0.57, "quantity": "force", "unit": "N"},
  "sensors": [{"channel": "acc1", "position_m": 0.1, "quantity": "acceleration", "unit": "m/s^2"}],
  "steps": [{"file": "low/step_000.csv", "frequency_Hz": 50.0, "level": "low"},
            {"file": "low/step_001.csv", "frequency_Hz": 50.5, "level": "low"},
            {"file": "high/step_000.csv", "frequency_Hz": 50.0, "level": "high"}]
})";
}

TEST(ReadCampaign, KeepsTheContentHashAndWarnsOfARecordingThatCopiesAnotherStep) {
  const fs::path folder = testing::UniqueTempPath("campaign_duplicate");
  fs::remove_all(folder);
  Write(folder / "campaign.json", CampaignJson());
  Write(folder / "low/step_000.csv", "time_s,force,acc1\n0,1,2\n");
  Write(folder / "low/step_001.csv", "time_s,force,acc1\n0,1,3\n");
  Write(folder / "high/step_000.csv", "time_s,force,acc1\n0,1,4\n");
  const Campaign distinct = ReadCampaign(folder);
  EXPECT_TRUE(distinct.warnings.empty());
  EXPECT_EQ(distinct.sha256,
            HashCampaign(folder, {"low/step_000.csv", "low/step_001.csv", "high/step_000.csv"}).sha256);

  fs::copy_file(folder / "low/step_000.csv", folder / "high/step_000.csv", fs::copy_options::overwrite_existing);
  const Campaign copied = ReadCampaign(folder);
  ASSERT_EQ(copied.warnings.size(), 1u);
  EXPECT_THAT(copied.warnings[0], HasSubstr((folder / "high/step_000.csv").string()));
  EXPECT_THAT(copied.warnings[0], HasSubstr("holds the same bytes as " + (folder / "low/step_000.csv").string()));
  EXPECT_NE(copied.sha256, distinct.sha256);

  // A file derived from the first campaign is refused against the second,
  // naming both files; one without the hash is refused as an older file.
  const CampaignOfFile derived{.file = "p.json", .sha256 = distinct.sha256, .name = distinct.name};
  EXPECT_NO_THROW(RequireDerivedFrom(derived, distinct, "extract again"));
  try {
    RequireDerivedFrom(derived, copied, "extract again");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("p.json"));
    EXPECT_THAT(e.what(), HasSubstr((folder / "campaign.json").string()));
    EXPECT_THAT(e.what(), HasSubstr("Fix: extract again"));
  }
  try {
    RequireDerivedFrom({.file = "old.json", .sha256 = "", .name = distinct.name}, distinct, "extract again");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("old.json: written by an older beamid"));
  }
  fs::remove_all(folder);
}

}  // namespace
}  // namespace beamid::signal
