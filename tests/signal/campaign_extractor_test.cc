// A small campaign on disk (CSV files in a temp folder, units in g and mm/s,
// one step with a transient): phasors equal those of the in-memory records,
// the thread count changes nothing, and bad steps are all listed together
// (or skipped and listed).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <random>

#include <unistd.h>

#include <gtest/gtest.h>

#include "signal/campaign_extractor.h"
#include "signal/input_error.h"
#include "tests/signal/synthetic_signal.h"

namespace beamid::signal {
namespace {

namespace fs = std::filesystem;
using testing::RandomTone;
using testing::Synthesize;
using testing::Tone;

constexpr double kRateHz = 4096.0;
constexpr int kSamples = 4096;

class CampaignExtractorTest : public ::testing::Test {
 protected:
  void SetUp() override {
    // One folder per test and process: ctest runs tests in parallel.
    folder_ = fs::temp_directory_path() /
              ("beamid_extractor_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()) +
               "_" + std::to_string(::getpid()));
    fs::remove_all(folder_);
    fs::create_directories(folder_ / "low");
    std::ofstream(folder_ / "campaign.json") << R"({
  "format": "stepped-sine-campaign/1", "name": "extractor test",
  "beam": {"length_m": 0.6, "width_m": 0.04, "thickness_m": 0.005, "youngs_modulus_Pa": 2.1e11, "density_kg_m3": 7850},
  "excitation": {"channel": "force", "position_m": 0.57, "quantity": "force", "unit": "N"},
  "sensors": [{"channel": "acc1", "position_m": 0.1, "quantity": "acceleration", "unit": "g"},
              {"channel": "vel2", "position_m": 0.3, "quantity": "velocity", "unit": "mm/s"}],
  "steps": [{"file": "low/s0.csv", "frequency_Hz": 40.0, "level": "low"},
            {"file": "low/s1.csv", "frequency_Hz": 41.0, "level": "low"},
            {"file": "low/s2.csv", "frequency_Hz": 42.0, "level": "low"},
            {"file": "low/s3.csv", "frequency_Hz": 43.0, "level": "low"}]
})";
    std::mt19937 rng(5);
    std::normal_distribution<double> normal;
    for (int s = 0; s < 4; ++s) {
      Eigen::MatrixXd si(kSamples, 3);  // SI values
      for (int c = 0; c < 3; ++c) {
        Tone tone = RandomTone(rng, 5, 40.0 + s + 0.013, 1.0 + c);
        tone.sample_rate_hz = kRateHz;
        si.col(c) = Synthesize(tone, kSamples, 0.0);
        for (int n = 0; n < kSamples; ++n) {
          const double t = n / kRateHz;
          if (s == 1) si(n, c) += (1.0 + c) * std::exp(-t / 0.02) * std::sin(2.0 * std::numbers::pi * 57.0 * t);
          si(n, c) += 1e-3 * (1.0 + c) * normal(rng);
        }
      }
      records_.push_back(si);
      std::string csv = "time_s,vel2,force,acc1\n";
      char line[200];
      for (int n = 0; n < kSamples; ++n) {
        std::snprintf(line, sizeof line, "%.10f,%.9g,%.9g,%.9g\n", n / kRateHz, si(n, 2) * 1e3, si(n, 0),
                      si(n, 1) / 9.80665);
        csv += line;
      }
      std::ofstream(folder_ / ("low/s" + std::to_string(s) + ".csv")) << csv;
    }
  }
  void TearDown() override { fs::remove_all(folder_); }

  fs::path folder_;
  std::vector<Eigen::MatrixXd> records_;
};

TEST_F(CampaignExtractorTest, FromDiskEqualsInMemoryForAnyThreadCount) {
  const Campaign campaign = ReadCampaign(folder_);
  ExtractOptions one;
  one.num_threads = 1;
  std::size_t calls = 0;
  one.progress = [&](std::size_t done, std::size_t total, const StepPhasors&) {
    EXPECT_EQ(total, 4u);
    EXPECT_EQ(done, ++calls);
  };
  const PhasorSet serial = ExtractCampaign(campaign, one);
  EXPECT_EQ(calls, 4u);
  ExtractOptions two;
  two.num_threads = 2;
  const PhasorSet parallel = ExtractCampaign(campaign, two);
  ASSERT_EQ(serial.steps.size(), 4u);
  ASSERT_EQ(parallel.steps.size(), 4u);
  EXPECT_EQ(serial.campaign, "extractor test");
  EXPECT_EQ(serial.num_harmonics, 5);
  for (std::size_t s = 0; s < 4; ++s) {
    EXPECT_EQ(serial.steps[s].file, "low/s" + std::to_string(s) + ".csv");
    EXPECT_NEAR(serial.steps[s].frequency_hz, 40.013 + s, 1e-4);
    EXPECT_EQ(serial.steps[s].frequency_hz, parallel.steps[s].frequency_hz);
    // The in-memory record (SI, no CSV rounding) gives the same phasors
    // within their uncertainty.
    Recording recording = testing::SyntheticRecording(campaign, records_[s], kRateHz);
    const StepPhasors memory = EstimateStepPhasors(recording, campaign, campaign.steps[s]);
    for (const auto& name : {"force", "acc1", "vel2"}) {
      const ChannelPhasors& a = *serial.steps[s].Find(name);
      const ChannelPhasors& b = *parallel.steps[s].Find(name);
      const ChannelPhasors& m = *memory.Find(name);
      for (int k = 1; k <= 5; ++k) {
        EXPECT_EQ(a.Harmonic(k).value, b.Harmonic(k).value);
        EXPECT_LT(std::abs(a.Harmonic(k).value - m.Harmonic(k).value), 0.05 * m.Harmonic(k).std_real + 1e-9)
            << name << " k=" << k;
      }
    }
  }
  EXPECT_EQ(serial.steps[1].responses[1].quantity, Quantity::kVelocity);
  EXPECT_GT(serial.steps[1].quality.settled_after_s, 0.05);
  EXPECT_EQ(serial.steps[0].quality.settled_after_s, 0.0);
}

TEST_F(CampaignExtractorTest, EveryBadStepIsListedTogetherOrSkipped) {
  // Step 2's force column has a NaN; step 3's file is cut short.
  std::string text;
  {
    std::ifstream in(folder_ / "low/s2.csv");
    text.assign(std::istreambuf_iterator<char>(in), {});
  }
  const std::size_t line = text.find('\n', text.find('\n') + 1) + 1;
  const std::size_t comma = text.find(',', text.find(',', line) + 1);
  text.replace(comma + 1, text.find(',', comma + 1) - comma - 1, "NaN");
  std::ofstream(folder_ / "low/s2.csv") << text;
  std::ofstream(folder_ / "low/s3.csv") << "time_s,vel2,force,acc1\n0,1,2,3\n";
  const PhasorSet clean_steps = [&] {
    ExtractOptions skip;
    skip.skip_bad_steps = true;
    return ExtractCampaign(ReadCampaign(folder_), skip);
  }();
  for (int threads : {1, 2}) {
    ExtractOptions options;
    options.num_threads = threads;
    try {
      ExtractCampaign(ReadCampaign(folder_), options);
      FAIL() << "no error";
    } catch (const InputError& e) {
      // Both bad steps, in campaign order, each with its file and problem,
      // and the way to analyse the rest.
      const std::string message = e.what();
      const std::size_t nan = message.find((folder_ / "low/s2.csv").string() + ": channel 'force': NaN or infinite "
                                           "value at line 3");
      const std::size_t short_file = message.find((folder_ / "low/s3.csv").string());
      EXPECT_NE(nan, std::string::npos) << message;
      EXPECT_NE(short_file, std::string::npos) << message;
      EXPECT_LT(nan, short_file) << message;
      EXPECT_NE(message.find("2 of 4 steps cannot be analysed"), std::string::npos) << message;
      EXPECT_NE(message.find("--skip-bad-steps"), std::string::npos) << message;
    }
  }
  // Skipped: the good steps as extracted alone, the bad ones listed with why.
  ASSERT_EQ(clean_steps.steps.size(), 2u);
  EXPECT_EQ(clean_steps.steps[0].file, "low/s0.csv");
  EXPECT_EQ(clean_steps.steps[1].file, "low/s1.csv");
  ASSERT_EQ(clean_steps.skipped.size(), 2u);
  EXPECT_EQ(clean_steps.skipped[0].file, "low/s2.csv");
  EXPECT_EQ(clean_steps.skipped[0].nominal_frequency_hz, 42.0);
  EXPECT_NE(clean_steps.skipped[0].reason.find("NaN"), std::string::npos);
  EXPECT_EQ(clean_steps.skipped[1].file, "low/s3.csv");
  const Campaign campaign = ReadCampaign(folder_);
  const Recording s0 = ReadRecording(campaign, campaign.steps[0]);
  const StepPhasors alone = EstimateStepPhasors(s0, campaign, campaign.steps[0]);
  EXPECT_EQ(clean_steps.steps[0].responses[0].Harmonic(1).value, alone.responses[0].Harmonic(1).value);
}

TEST_F(CampaignExtractorTest, AColumnNoChannelUsesIsIgnoredAndSaid) {
  // Step 0 gains a temperature column an acquisition system wrote beside the
  // channels: the step is analysed as before and the column named once.
  std::ifstream in(folder_ / "low/s0.csv");
  std::string text((std::istreambuf_iterator<char>(in)), {});
  std::string with_extra;
  std::size_t start = 0;
  for (bool header = true; start < text.size(); header = false) {
    const std::size_t end = text.find('\n', start);
    with_extra += text.substr(start, end - start) + (header ? ",temperature [degC]\n" : ",21.5\n");
    start = end + 1;
  }
  const PhasorSet clean = ExtractCampaign(ReadCampaign(folder_), {});
  std::ofstream(folder_ / "low/s0.csv") << with_extra;
  const PhasorSet set = ExtractCampaign(ReadCampaign(folder_), {});
  EXPECT_EQ(set.steps[0].force.Harmonic(1).value, clean.steps[0].force.Harmonic(1).value);
  EXPECT_EQ(set.steps[0].responses[1].Harmonic(3).value, clean.steps[0].responses[1].Harmonic(3).value);
  const auto& warnings = set.steps[0].quality.warnings;
  EXPECT_EQ(std::count(warnings.begin(), warnings.end(), "columns no channel uses, ignored: temperature [degC]"), 1);
  for (const auto& w : set.steps[1].quality.warnings) EXPECT_EQ(w.find("ignored"), std::string::npos) << w;
}

}  // namespace
}  // namespace beamid::signal
