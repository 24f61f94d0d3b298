// Universal files (dataset 58, ASCII and binary) as step recordings: a
// campaign written as UFF in five encodings gives the phasors of the same
// samples written as CSV, and each malformed file gives an InputError naming
// the file, the channel and what is wrong, quoting at most a short printable
// excerpt of the file; a record 9 unit must be campaign.json's (as a CSV
// header's must); the problems of a channel campaign.json ignores are notes.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <random>

#include <gtest/gtest.h>

#include "signal/campaign_extractor.h"
#include "signal/input_error.h"
#include "signal/internal/text.h"
#include "signal/recording.h"
#include "tests/signal/synthetic_signal.h"
#include "tests/signal/uff58_writer.h"
#include "tests/support/memory_in_child.h"
#include "tests/support/temp_path.h"

namespace beamid::signal {
namespace {

namespace fs = std::filesystem;
using beamid::testing::UffChannel;
using beamid::testing::UffEncoding;

constexpr double kRateHz = 5000.0;  // dx = 2e-4 s is exact in E13.5
constexpr int kSamples = 5000;
constexpr int kSteps = 2;
constexpr double kGravity = 9.80665;

std::string CampaignJson(const std::string& extension) {
  std::string steps;
  for (int s = 0; s < kSteps; ++s)
    steps += std::string(s ? "," : "") + R"({"file": "s)" + std::to_string(s) + extension +
             R"(", "frequency_Hz": )" + std::to_string(40 + s) + R"(, "level": "low"})";
  return R"({
  "format": "stepped-sine-campaign/1", "name": "uff test",
  "beam": {"length_m": 0.6, "width_m": 0.04, "thickness_m": 0.005, "youngs_modulus_Pa": 2.1e11, "density_kg_m3": 7850},
  "excitation": {"channel": "force", "position_m": 0.57, "quantity": "force", "unit": "N"},
  "sensors": [{"channel": "acc1", "position_m": 0.1, "quantity": "acceleration", "unit": "g"},
              {"channel": "vel2", "position_m": 0.3, "quantity": "velocity", "unit": "mm/s"}],
  "steps": [)" + steps + "]}";
}

// The three channels of a step in the campaign's units (N, g, mm/s), as the
// encoding stores them.
struct StepData {
  std::vector<std::vector<double>> columns;  // force, acc1, vel2
};

std::vector<StepData> MakeSteps(UffEncoding encoding) {
  std::mt19937 rng(11);
  std::normal_distribution<double> noise;
  std::vector<StepData> steps(kSteps);
  const double to_file[] = {1.0, 1.0 / kGravity, 1e3};
  for (int s = 0; s < kSteps; ++s)
    for (int c = 0; c < 3; ++c) {
      testing::Tone tone = testing::RandomTone(rng, 5, 40.0 + s + 0.011, 1.0 + c);
      tone.sample_rate_hz = kRateHz;
      const Eigen::VectorXd si = testing::Synthesize(tone, kSamples, 0.0);
      std::vector<double> column(kSamples);
      for (int n = 0; n < kSamples; ++n)
        column[n] = beamid::testing::StoredValue((si[n] + 1e-3 * (1.0 + c) * noise(rng)) * to_file[c], encoding);
      steps[s].columns.push_back(column);
    }
  return steps;
}

std::vector<UffChannel> UffChannels(const StepData& step, bool names_in_entity) {
  const char* names[] = {"force", "acc1", "vel2"};
  const int data_types[] = {13, 12, 11};
  const char* units[] = {"N", "g", "mm/s"};
  std::vector<UffChannel> channels(3);
  for (int c = 0; c < 3; ++c) {
    UffChannel& ch = channels[c];
    ch.id_line1 = names_in_entity ? "Point " + std::to_string(c + 1) + " +Z" : names[c];
    if (names_in_entity) ch.entity = names[c];
    ch.node = c + 1;
    ch.ordinate_data_type = data_types[c];
    ch.unit = names_in_entity ? "" : units[c];  // blank: campaign.json's unit applies
    ch.dx = 1.0 / kRateHz;
    ch.values = step.columns[c];
  }
  return channels;
}

std::string UffFile(const std::vector<UffChannel>& channels, UffEncoding encoding) {
  std::string text = beamid::testing::Uff151Header();
  // Channels in another order than campaign.json.
  for (int c : {2, 0, 1}) text += beamid::testing::UffDataset58(channels[c], encoding);
  return text;
}

void WriteFile(const fs::path& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary) << bytes;
}

class UffRecordingTest : public ::testing::TestWithParam<UffEncoding> {
 protected:
  void SetUp() override {
    folder_ = beamid::testing::UniqueTempPath("beamid_uff");
    fs::remove_all(folder_);
    fs::create_directories(folder_ / "csv");
    fs::create_directories(folder_ / "uff");
  }
  void TearDown() override { fs::remove_all(folder_); }
  fs::path folder_;
};

TEST_P(UffRecordingTest, GivesThePhasorsOfTheSameSamplesAsCsv) {
  const UffEncoding encoding = GetParam();
  const std::vector<StepData> steps = MakeSteps(encoding);
  WriteFile(folder_ / "csv/campaign.json", CampaignJson(".csv"));
  WriteFile(folder_ / "uff/campaign.json", CampaignJson(".uff"));
  for (int s = 0; s < kSteps; ++s) {
    std::string csv = "time_s,force,acc1,vel2\n";
    char line[200];
    for (int n = 0; n < kSamples; ++n) {
      std::snprintf(line, sizeof line, "%.4f,%.17g,%.17g,%.17g\n", n / kRateHz, steps[s].columns[0][n],
                    steps[s].columns[1][n], steps[s].columns[2][n]);
      csv += line;
    }
    WriteFile(folder_ / ("csv/s" + std::to_string(s) + ".csv"), csv);
    WriteFile(folder_ / ("uff/s" + std::to_string(s) + ".uff"),
              UffFile(UffChannels(steps[s], beamid::testing::IsBinary(encoding)), encoding));
  }
  const Campaign uff_campaign = ReadCampaign(folder_ / "uff");
  const Recording recording = ReadRecording(uff_campaign, uff_campaign.steps[0]);
  EXPECT_DOUBLE_EQ(recording.sample_rate_hz, kRateHz);
  ASSERT_EQ(recording.NumSamples(), kSamples);
  EXPECT_EQ(recording.samples(7, 1), steps[0].columns[1][7] * kGravity);  // g → m/s²
  EXPECT_EQ(recording.samples(7, 2), steps[0].columns[2][7] * 1e-3);      // mm/s → m/s

  const PhasorSet from_csv = ExtractCampaign(ReadCampaign(folder_ / "csv"));
  const PhasorSet from_uff = ExtractCampaign(uff_campaign);
  ASSERT_EQ(from_uff.steps.size(), static_cast<std::size_t>(kSteps));
  for (int s = 0; s < kSteps; ++s) {
    EXPECT_NEAR(from_uff.steps[s].frequency_hz, from_csv.steps[s].frequency_hz, 1e-9);
    for (const char* name : {"force", "acc1", "vel2"}) {
      const ChannelPhasors& a = *from_uff.steps[s].Find(name);
      const ChannelPhasors& b = *from_csv.steps[s].Find(name);
      const double scale = b.Harmonic(1).Amplitude();
      for (int k = 1; k <= 5; ++k)
        EXPECT_LT(std::abs(a.Harmonic(k).value - b.Harmonic(k).value), 1e-9 * scale)
            << name << " step " << s << " k=" << k;
    }
  }
}

std::string EncodingName(const ::testing::TestParamInfo<UffEncoding>& param) {
  static const char* const kNames[] = {"AsciiSingle", "AsciiDouble", "BinaryLittleFloat", "BinaryLittleDouble",
                                       "BinaryBigDouble"};
  return kNames[static_cast<int>(param.param)];
}

INSTANTIATE_TEST_SUITE_P(Encodings, UffRecordingTest,
                         ::testing::Values(UffEncoding::kAsciiSingle, UffEncoding::kAsciiDouble,
                                           UffEncoding::kBinaryLittleFloat, UffEncoding::kBinaryLittleDouble,
                                           UffEncoding::kBinaryBigDouble),
                         EncodingName);

// One malformed file per case: the error names the file, the channel (when
// one is concerned) and what is wrong.
class UffMalformedTest : public ::testing::Test {
 protected:
  void SetUp() override {
    folder_ = beamid::testing::UniqueTempPath("beamid_uff_bad");
    fs::remove_all(folder_);
    fs::create_directories(folder_);
    WriteFile(folder_ / "campaign.json", CampaignJson(".unv"));
    channels_ = UffChannels(MakeSteps(UffEncoding::kAsciiDouble)[0], false);
  }
  void TearDown() override { fs::remove_all(folder_); }

  void ExpectError(const std::string& bytes, const std::string& channel, const std::string& problem) {
    WriteFile(folder_ / "s0.unv", bytes);
    WriteFile(folder_ / "s1.unv", bytes);
    const Campaign campaign = ReadCampaign(folder_);
    try {
      ReadRecording(campaign, campaign.steps[0]);
      FAIL() << "no error for " << problem;
    } catch (const InputError& e) {
      EXPECT_EQ(e.file(), (folder_ / "s0.unv").string());
      EXPECT_EQ(e.channel(), channel) << e.what();
      EXPECT_NE(std::string(e.what()).find(problem), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("Fix: "), std::string::npos) << e.what();
    }
  }

  std::string File(UffEncoding encoding = UffEncoding::kAsciiDouble) const { return UffFile(channels_, encoding); }

  fs::path folder_;
  std::vector<UffChannel> channels_;
};

TEST_F(UffMalformedTest, WellFormedFileReads) {
  WriteFile(folder_ / "s0.unv", File());
  WriteFile(folder_ / "s1.unv", File());
  const Campaign campaign = ReadCampaign(folder_);
  EXPECT_EQ(ReadRecording(campaign, campaign.steps[0]).NumSamples(), kSamples);
}

TEST_F(UffMalformedTest, MissingChannel) {
  std::string text = beamid::testing::UffDataset58(channels_[0], UffEncoding::kAsciiDouble) +
                     beamid::testing::UffDataset58(channels_[1], UffEncoding::kAsciiDouble);
  ExpectError(text, "vel2", "no dataset 58 holds the channel");
}

TEST_F(UffMalformedTest, UnknownChannel) {
  channels_[2].id_line1 = "Vel 2";
  ExpectError(File(), "Vel 2", "names no channel of campaign.json");
}

TEST_F(UffMalformedTest, MismatchedSampling) {
  channels_[1].dx = 1.0 / 4096.0;
  ExpectError(File(), "acc1", "every 0.000244141 s, but channel 'force' has 5000 samples");
}

TEST_F(UffMalformedTest, NaN) {
  channels_[1].values[100] = std::nan("");
  ExpectError(File(UffEncoding::kBinaryLittleDouble), "acc1", "NaN or infinite value at sample 100");
}

TEST_F(UffMalformedTest, UnknownUnit) {
  channels_[1].unit = "in/s^2";
  ExpectError(File(), "acc1", "unit 'in/s^2' (record 9) is not accepted");
}

TEST_F(UffMalformedTest, QuantityDisagreesWithCampaign) {
  channels_[2].ordinate_data_type = 12;  // acceleration, but vel2 is a velocity
  ExpectError(File(), "vel2", "holds acceleration");
}

TEST_F(UffMalformedTest, TruncatedAscii) {
  const std::string text = File();
  ExpectError(text.substr(0, text.size() - 3000), "", "truncated");
}

TEST_F(UffMalformedTest, TruncatedBinary) {
  const std::string text = File(UffEncoding::kBinaryLittleFloat);
  ExpectError(text.substr(0, text.size() - 3000), "", "truncated");
}

TEST_F(UffMalformedTest, ComplexOrdinate) {
  channels_[0].ordinate_type = 6;
  ExpectError(File(), "", "ordinate data type 6 (complex)");
}

TEST_F(UffMalformedTest, UnevenAbscissa) {
  channels_[0].spacing = 0;
  ExpectError(File(), "", "unevenly spaced");
}

TEST_F(UffMalformedTest, FrequencyResponseFunction) {
  channels_[0].function_type = 4;
  ExpectError(File(), "", "function type 4 (frequency response function) is not a time history");
}

TEST_F(UffMalformedTest, NotAUniversalFile) {
  ExpectError("time_s,force\n0,1\n", "", "should open a dataset with -1");
}

// A g where campaign.json says m/s² is a factor 9.81 that beamid will not
// guess: refused as a CSV header's unit is, naming both units.
TEST_F(UffMalformedTest, UnitDisagreesWithCampaign) {
  channels_[1].unit = "m/s^2";  // campaign.json: g
  ExpectError(File(), "acc1", "record 9 gives the unit 'm/s^2' but campaign.json declares 'g' for this channel");
  ExpectError(File(), "acc1", "Fix: make them agree: correct the channel's \"unit\" in campaign.json, or export");
  // The Latin-1 ² of many writers is m/s² too, and quoted printable.
  channels_[1].unit = "m/s\xB2";
  ExpectError(File(), "acc1", "record 9 gives the unit 'm/s\\xB2' but campaign.json declares 'g'");
}

TEST_F(UffMalformedTest, AValueBeyondADoubleIsOutOfRange) {
  channels_[0].values[3] = 12345.678;
  std::string text = File();
  const std::size_t at = text.find("1.234567800000E+04");
  ASSERT_NE(at, std::string::npos);
  text.replace(at, 18, "             1e400");
  ExpectError(text, "", "'1e400' is out of range");
}

// A file of zeros: refused at its first line, quoting a short excerpt of it,
// in memory of the file's size.
TEST_F(UffMalformedTest, ABigFileOfNulBytesIsRefusedInMemoryOfItsSize) {
  constexpr long long kBytes = 50LL << 20;
  {
    std::ofstream out(folder_ / "s0.unv", std::ios::binary);
    const std::string zeros(1 << 20, '\0');
    for (long long written = 0; written < kBytes; written += static_cast<long long>(zeros.size())) out << zeros;
  }
  WriteFile(folder_ / "s1.unv", File());
  const Campaign campaign = ReadCampaign(folder_);
  const auto run = beamid::testing::MemoryInChild(3 * kBytes, [&] {
    try {
      ReadRecording(campaign, campaign.steps[0]);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  });
  ASSERT_TRUE(run.ran);
  std::cout << "  50 MB of NUL bytes as a universal file: peak resident growth " << run.growth_bytes / (1 << 20)
            << " MB\n";
  EXPECT_NE(run.text.find("line 1 should open a dataset with -1 but reads '\\x00\\x00"), std::string::npos)
      << run.text.substr(0, 500);
  EXPECT_NE(run.text.find("(52428800 bytes)"), std::string::npos) << run.text.substr(0, 500);
  EXPECT_LT(run.text.size(), 500u);
  EXPECT_LT(run.growth_bytes, 3 * kBytes);
}

TEST_F(UffMalformedTest, MessagesQuoteShortPrintableUtf8) {
  channels_[2].id_line1 = "Vel \xE9\x01" + std::string(70, 'v');
  WriteFile(folder_ / "s0.unv", File());
  WriteFile(folder_ / "s1.unv", File());
  const Campaign campaign = ReadCampaign(folder_);
  try {
    ReadRecording(campaign, campaign.steps[0]);
    FAIL() << "accepted";
  } catch (const InputError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("ID line 1 'Vel \\xE9\\x01vvv"), std::string::npos) << message;
    EXPECT_TRUE(internal::IsValidUtf8(message)) << message;
    EXPECT_LT(message.size(), 800u) << message;
  }
}

// Problems of a channel campaign.json ignores are notes: the channel is left
// out and the step read without it.
TEST_F(UffMalformedTest, ProblemsOfAnIgnoredChannelAreNotes) {
  std::string json = CampaignJson(".unv");
  json.insert(json.rfind('}'), R"(, "ignore_channels": ["vel2"])");
  WriteFile(folder_ / "campaign.json", json);
  const std::vector<UffChannel> clean = channels_;
  struct Case {
    std::string what, problem;
    std::function<std::string()> file;
  };
  const std::vector<Case> cases = {
      {"NaN", "NaN or infinite value at sample 100",
       [&] {
         channels_ = clean;
         channels_[2].values[100] = std::nan("");
         return File(UffEncoding::kBinaryLittleDouble);
       }},
      {"another unit", "record 9 gives the unit 'm/s' but campaign.json declares 'mm/s'",
       [&] {
         channels_ = clean;
         channels_[2].unit = "m/s";
         return File();
       }},
      {"missing", "no dataset 58 holds the channel",
       [&] {
         channels_ = clean;
         return beamid::testing::UffDataset58(channels_[0], UffEncoding::kAsciiDouble) +
                beamid::testing::UffDataset58(channels_[1], UffEncoding::kAsciiDouble);
       }},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.what);
    const std::string bytes = c.file();
    WriteFile(folder_ / "s0.unv", bytes);
    WriteFile(folder_ / "s1.unv", bytes);
    const Campaign campaign = ReadCampaign(folder_);
    const Recording recording = ReadRecording(campaign, campaign.steps[0]);
    EXPECT_EQ(recording.channels, (std::vector<std::string>{"force", "acc1"}));
    EXPECT_EQ(recording.samples.cols(), 2);
    ASSERT_EQ(recording.findings.size(), 1u);
    EXPECT_EQ(recording.findings[0].severity, Severity::kNote);
    EXPECT_EQ(recording.findings[0].channel, "vel2");
    EXPECT_NE(recording.findings[0].problem.find(c.problem), std::string::npos) << recording.findings[0].problem;
    EXPECT_NE(recording.findings[0].problem.find("the channel is left out of this step"), std::string::npos);
  }
}

}  // namespace
}  // namespace beamid::signal
