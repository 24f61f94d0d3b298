// Graded quality checks on a campaign on disk (one step, force + acc1..acc3):
//  - problems of channels the analysis uses are errors, all listed together;
//  - the same problems on channels it does not use are warnings beside the
//    result, which is that of a clean recording bit for bit (the steady state
//    is judged on the analysed channels only);
//  - on channels campaign.json ignores they are notes;
//  - so are the problems of reading such a channel (a NaN, a cell that is no
//    number, a missing column, another unit than campaign.json's): the
//    channel is left out of the step, which the other channels give as a
//    clean recording does;
//  - campaign.json's ignore_channels and Campaign::Analyse refuse what makes
//    no sense, naming the entry.
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <numbers>
#include <random>
#include <string>

#include <unistd.h>

#include <gtest/gtest.h>

#include "signal/campaign_extractor.h"
#include "signal/input_error.h"
#include "tests/signal/synthetic_signal.h"
#include "tests/support/expect_refused.h"

namespace beamid::signal {
namespace {

namespace fs = std::filesystem;

constexpr double kRateHz = 4096.0;
constexpr int kSamples = 8192;
constexpr double kFrequencyHz = 40.0;

std::string CampaignJson(const std::string& extra) {
  return R"({
  "format": "stepped-sine-campaign/1", "name": "graded",
  "beam": {"length_m": 0.6, "width_m": 0.04, "thickness_m": 0.005, "youngs_modulus_Pa": 2.1e11, "density_kg_m3": 7850},
  "excitation": {"channel": "force", "position_m": 0.57, "quantity": "force", "unit": "N"},
  "sensors": [{"channel": "acc1", "position_m": 0.1, "quantity": "acceleration", "unit": "m/s^2"},
              {"channel": "acc2", "position_m": 0.3, "quantity": "acceleration", "unit": "m/s^2"},
              {"channel": "acc3", "position_m": 0.5, "quantity": "acceleration", "unit": "m/s^2"}],
  "steps": [{"file": "s0.csv", "frequency_Hz": 40.0, "level": "low"}])" +
         extra + "\n}";
}

class GradedChecksTest : public ::testing::Test {
 protected:
  void SetUp() override {
    folder_ = fs::temp_directory_path() /
              ("beamid_graded_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()) + "_" +
               std::to_string(::getpid()));
    fs::remove_all(folder_);
    fs::create_directories(folder_);
    std::mt19937 rng(11);
    std::normal_distribution<double> normal;
    samples_.resize(kSamples, 4);
    for (int c = 0; c < 4; ++c) {
      testing::Tone tone = testing::RandomTone(rng, 3, kFrequencyHz, 1.0 + c);
      tone.sample_rate_hz = kRateHz;
      samples_.col(c) = testing::Synthesize(tone, kSamples, 0.0);
      for (int n = 0; n < kSamples; ++n) samples_(n, c) += 1e-3 * normal(rng);
    }
  }
  void TearDown() override { fs::remove_all(folder_); }

  void Write(const Eigen::MatrixXd& samples, const std::string& campaign_extra = "") {
    std::ofstream(folder_ / "campaign.json") << CampaignJson(campaign_extra);
    std::ofstream csv(folder_ / "s0.csv");
    csv << "time_s,force,acc1,acc2,acc3\n";
    char line[200];
    for (int n = 0; n < kSamples; ++n) {
      std::snprintf(line, sizeof line, "%.10f,%.9g,%.9g,%.9g,%.9g\n", n / kRateHz, samples(n, 0), samples(n, 1),
                    samples(n, 2), samples(n, 3));
      csv << line;
    }
  }

  // acc2 clipped at 80 % of its peak, acc3 dropping out for 0.1 s and still
  // ringing (a loose sensor) over the first half of the record.
  Eigen::MatrixXd Faulty() const {
    Eigen::MatrixXd samples = samples_;
    const double limit = 0.8 * samples.col(2).cwiseAbs().maxCoeff();
    samples.col(2) = samples.col(2).cwiseMin(limit).cwiseMax(-limit);
    for (int n = 0; n < kSamples; ++n) {
      const double t = n / kRateHz;
      samples(n, 3) += 4.0 * std::exp(-t / 0.4) * std::sin(2.0 * std::numbers::pi * 77.0 * t);
    }
    samples.col(3).segment(4000, 410).setZero();
    return samples;
  }

  PhasorSet Extract(const std::vector<std::string>& analysed) const {
    Campaign campaign = ReadCampaign(folder_);
    campaign.Analyse(analysed);
    return ExtractCampaign(campaign, {});
  }

  fs::path folder_;
  Eigen::MatrixXd samples_;
};

bool Mentions(const std::vector<std::string>& lines, const std::string& text) {
  for (const auto& line : lines)
    if (line.find(text) != std::string::npos) return true;
  return false;
}

TEST_F(GradedChecksTest, ProblemsOfAnalysedChannelsAreErrorsListedTogether) {
  Write(Faulty());
  const std::string message = beamid::testing::InputErrorOf([&] { Extract({}); });
  EXPECT_NE(message.find("2 problems"), std::string::npos) << message;
  EXPECT_NE(message.find("channel 'acc2': clipped"), std::string::npos) << message;
  EXPECT_NE(message.find("channel 'acc3': dropout"), std::string::npos) << message;
  EXPECT_NE(message.find((folder_ / "s0.csv").string()), std::string::npos) << message;
}

TEST_F(GradedChecksTest, ProblemsOfOtherChannelsOnlyWarnAndChangeNothing) {
  Write(samples_);
  const PhasorSet clean = Extract({"acc1"});
  Write(Faulty());
  const PhasorSet set = Extract({"acc1"});
  ASSERT_EQ(set.steps.size(), 1u);
  const StepQuality& quality = set.steps[0].quality;
  EXPECT_TRUE(Mentions(quality.warnings, "channel 'acc2' (not analysed): clipped")) << quality.warnings.size();
  EXPECT_TRUE(Mentions(quality.warnings, "channel 'acc3' (not analysed): dropout"));
  // acc3's ringing does not cut the analysed channels' record.
  EXPECT_EQ(quality.settled_after_s, clean.steps[0].quality.settled_after_s) << quality.settling;
  EXPECT_EQ(set.steps[0].responses[0].Harmonic(1).value, clean.steps[0].responses[0].Harmonic(1).value);
  EXPECT_EQ(set.steps[0].force.Harmonic(2).value, clean.steps[0].force.Harmonic(2).value);
  // Analysing acc3 too makes its problem an error again.
  EXPECT_NE(beamid::testing::InputErrorOf([&] { Extract({"acc1", "acc3"}); }).find("channel 'acc3': dropout"),
            std::string::npos);
}

TEST_F(GradedChecksTest, ProblemsOfIgnoredChannelsAreNotes) {
  Write(Faulty(), R"(, "ignore_channels": ["acc2", "acc3"])");
  const PhasorSet set = Extract({});
  const StepQuality& quality = set.steps[0].quality;
  EXPECT_TRUE(Mentions(quality.notes, "channel 'acc2' (ignored in campaign.json): clipped"));
  EXPECT_TRUE(Mentions(quality.notes, "channel 'acc3' (ignored in campaign.json): dropout"));
  EXPECT_FALSE(Mentions(quality.warnings, "acc2"));
  EXPECT_FALSE(Mentions(quality.warnings, "acc3"));
}

// One line that holds both texts.
bool MentionsBoth(const std::vector<std::string>& lines, const std::string& a, const std::string& b) {
  for (const auto& line : lines)
    if (line.find(a) != std::string::npos && line.find(b) != std::string::npos) return true;
  return false;
}

// The CSV text of s0.csv, edited by `edit`.
void EditCsv(const fs::path& file, const std::function<void(std::string&)>& edit) {
  std::stringstream text;
  text << std::ifstream(file).rdbuf();
  std::string csv = text.str();
  edit(csv);
  std::ofstream(file, std::ios::binary) << csv;
}

// Replaces acc3's value (the fifth cell) on file line `line`.
void SetAcc3(std::string& csv, int line, const std::string& value) {
  std::size_t start = 0;
  for (int i = 1; i < line; ++i) start = csv.find('\n', start) + 1;
  std::size_t cell = start;
  for (int i = 0; i < 4; ++i) cell = csv.find(',', cell) + 1;
  csv.replace(cell, csv.find('\n', cell) - cell, value);
}

TEST_F(GradedChecksTest, ReadingProblemsOfChannelsNotUsedAreNotesOrWarningsAndLeaveTheChannelOut) {
  Write(samples_);
  const PhasorSet clean = Extract({});
  struct Case {
    std::string what;
    std::function<void(std::string&)> edit;
    std::string problem;
  };
  const std::vector<Case> cases = {
      {"NaN", [](std::string& csv) { SetAcc3(csv, 100, "nan"); }, "NaN or infinite value at line 100"},
      {"no number", [](std::string& csv) { SetAcc3(csv, 100, "1.2.3"); },
       "line 100, column acc3: '1.2.3' is not a number"},
      {"out of range", [](std::string& csv) { SetAcc3(csv, 7, "1e400"); }, "'1e400' is out of range"},
      {"beyond any measurement", [](std::string& csv) { SetAcc3(csv, 7, "1e20"); }, "beyond any measurement"},
      {"missing column", [](std::string& csv) { csv.replace(csv.find("acc3"), 4, "acc9"); },
       "missing from the header (columns no channel uses: 'acc9')"},
      {"another unit", [](std::string& csv) { csv.replace(csv.find("acc3"), 4, "acc3 [g]"); },
       "the header gives the unit 'g' but campaign.json declares 'm/s^2'"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.what);
    // Ignored in campaign.json: a note.
    Write(samples_, R"(, "ignore_channels": ["acc3"])");
    EditCsv(folder_ / "s0.csv", c.edit);
    const PhasorSet ignored = Extract({});
    ASSERT_EQ(ignored.steps.size(), 1u);
    const StepQuality& quality = ignored.steps[0].quality;
    EXPECT_TRUE(MentionsBoth(quality.notes, "channel 'acc3' (ignored in campaign.json): ", c.problem))
        << (quality.notes.empty() ? "no notes" : quality.notes[0]);
    EXPECT_TRUE(MentionsBoth(quality.notes, c.problem, "; the channel is left out of this step"));
    EXPECT_FALSE(Mentions(quality.warnings, "acc3"));
    EXPECT_EQ(ignored.steps[0].Find("acc3"), nullptr);
    EXPECT_EQ(ignored.steps[0].responses.size(), 2u);
    EXPECT_EQ(ignored.steps[0].Find("acc1")->Harmonic(1).value, clean.steps[0].Find("acc1")->Harmonic(1).value);
    EXPECT_EQ(ignored.steps[0].force.Harmonic(2).value, clean.steps[0].force.Harmonic(2).value);

    // Not analysed by this run: a warning. Analysed: an error naming it.
    Write(samples_);
    EditCsv(folder_ / "s0.csv", c.edit);
    const PhasorSet unused = Extract({"acc1"});
    EXPECT_TRUE(MentionsBoth(unused.steps[0].quality.warnings, "channel 'acc3' (not analysed): ", c.problem));
    EXPECT_EQ(unused.steps[0].Find("acc3"), nullptr);
    const std::string message = beamid::testing::InputErrorOf([&] { Extract({}); });
    EXPECT_NE(message.find("channel 'acc3': "), std::string::npos) << message;
    EXPECT_NE(message.find(c.problem), std::string::npos) << message;
    EXPECT_NE(message.find((folder_ / "s0.csv").string()), std::string::npos) << message;
  }
}

TEST_F(GradedChecksTest, IgnoreChannelsAndAnalyseRefuseWhatMakesNoSense) {
  for (const auto& [extra, expected] : std::vector<std::pair<std::string, std::string>>{
           {R"(, "ignore_channels": "acc2")", "field \"ignore_channels\" must be an array"},
           {R"(, "ignore_channels": ["acc9"])", "ignore_channels[0]: names no sensor"},
           {R"(, "ignore_channels": ["force"])", "the excitation cannot be ignored"},
           {R"(, "ignore_channels": ["acc2", "acc2"])", "ignore_channels[1]: the channel is listed twice"},
           {R"(, "ignore_channels": [3])", "field \"ignore_channels[0]\" must be a string"}}) {
    Write(samples_, extra);
    const std::string message = beamid::testing::InputErrorOf([&] { ReadCampaign(folder_); });
    EXPECT_NE(message.find(expected), std::string::npos) << extra << " -> " << message;
  }
  Write(samples_, R"(, "ignore_channels": ["acc2"])");
  Campaign campaign = ReadCampaign(folder_);
  EXPECT_EQ(campaign.Use("acc2"), ChannelUse::kIgnored);
  EXPECT_EQ(campaign.Use("force"), ChannelUse::kUsed);
  EXPECT_NE(beamid::testing::InputErrorOf([&] { campaign.Analyse({"acc2"}); }).find("listed in ignore_channels"),
            std::string::npos);
  EXPECT_NE(beamid::testing::InputErrorOf([&] { campaign.Analyse({"accX"}); }).find("is not a sensor of the campaign"),
            std::string::npos);
  campaign.Analyse({"acc3"});
  EXPECT_EQ(campaign.Use("acc1"), ChannelUse::kUnused);
  EXPECT_EQ(campaign.Use("acc3"), ChannelUse::kUsed);
}

}  // namespace
}  // namespace beamid::signal
