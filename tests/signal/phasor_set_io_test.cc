// phasors.json round trip (every field the solver reads survives exactly),
// the CSV view's shape, and errors for files that are not phasor files.
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "signal/input_error.h"
#include "signal/phasor_set_io.h"
#include "tests/support/schema_checks.h"

namespace beamid::signal {
namespace {

PhasorSet Example() {
  PhasorSet set;
  set.campaign = "io test";
  set.campaign_sha256 = "9f86d081884c7d659a2feaa0c55ad015a3bf4f1b2b0b822cd15d6c15b0f00a08";
  set.num_harmonics = 2;
  for (int s = 0; s < 2; ++s) {
    StepPhasors step;
    step.file = "low/step_00" + std::to_string(s) + ".csv";
    step.level = "low";
    step.nominal_frequency_hz = 50.0 + 0.25 * s;
    step.frequency_hz = step.nominal_frequency_hz * (1.0 + 2.5e-5) + 1e-13;
    step.frequency_std_hz = 3.3e-6;
    step.quality = {41.25, 0.125, 0.875, "transient dropped: ...", {"a warning", "another"}};
    if (s == 1) {
      step.quality.unsettled = true;
      step.quality.unsettled_change_relative = 0.016 / 3.0;
      step.quality.unsettled_channel = "acc2";
    }
    for (int c = 0; c < 3; ++c) {
      ChannelPhasors channel;
      channel.channel = c == 0 ? "force" : "acc" + std::to_string(c);
      channel.quantity = c == 0 ? Quantity::kForce : Quantity::kAcceleration;
      channel.position_m = 0.1 * c + 1.0 / 3.0;
      channel.mean = -1e-3 / 7.0;
      channel.thd = 0.0123;
      channel.snr_db = 55.5;
      channel.noise_rms = 1.1e-3;
      for (int k = 1; k <= 2; ++k) {
        HarmonicPhasor h;
        h.harmonic = k;
        h.value = {1.0 / (3.0 * k) + c, c == 0 && k == 1 ? 0.0 : -2.0 / 7.0};
        h.std_real = 1e-4 / 3.0;
        h.std_imag = c == 0 && k == 1 ? 0.0 : 2e-4 / 3.0;
        h.correlation = -0.1 / 3.0;
        channel.harmonics.push_back(h);
      }
      if (c == 0)
        step.force = channel;
      else
        step.responses.push_back(channel);
    }
    set.steps.push_back(step);
  }
  return set;
}

void ExpectSameChannel(const ChannelPhasors& a, const ChannelPhasors& b) {
  EXPECT_EQ(a.channel, b.channel);
  EXPECT_EQ(a.quantity, b.quantity);
  EXPECT_EQ(a.position_m, b.position_m);
  EXPECT_EQ(a.mean, b.mean);
  EXPECT_EQ(a.thd, b.thd);
  EXPECT_EQ(a.snr_db, b.snr_db);
  EXPECT_EQ(a.noise_rms, b.noise_rms);
  ASSERT_EQ(a.harmonics.size(), b.harmonics.size());
  for (std::size_t k = 0; k < a.harmonics.size(); ++k) {
    EXPECT_EQ(a.harmonics[k].harmonic, b.harmonics[k].harmonic);
    EXPECT_EQ(a.harmonics[k].value, b.harmonics[k].value);
    EXPECT_EQ(a.harmonics[k].std_real, b.harmonics[k].std_real);
    EXPECT_EQ(a.harmonics[k].std_imag, b.harmonics[k].std_imag);
    EXPECT_EQ(a.harmonics[k].correlation, b.harmonics[k].correlation);
  }
}

TEST(PhasorSetIoTest, JsonRoundTripIsExact) {
  const PhasorSet set = Example();
  const auto file = std::filesystem::temp_directory_path() / "beamid_phasor_io_test.json";
  WritePhasorSetJson(set, file);
  const PhasorSet back = ReadPhasorSetJson(file);
  std::filesystem::remove(file);
  EXPECT_EQ(back.campaign, set.campaign);
  EXPECT_EQ(back.campaign_sha256, set.campaign_sha256);
  EXPECT_EQ(back.num_harmonics, 2);
  ASSERT_EQ(back.steps.size(), 2u);
  for (std::size_t s = 0; s < 2; ++s) {
    const StepPhasors& a = set.steps[s];
    const StepPhasors& b = back.steps[s];
    EXPECT_EQ(a.file, b.file);
    EXPECT_EQ(a.level, b.level);
    EXPECT_EQ(a.nominal_frequency_hz, b.nominal_frequency_hz);
    EXPECT_EQ(a.frequency_hz, b.frequency_hz);
    EXPECT_EQ(a.frequency_std_hz, b.frequency_std_hz);
    EXPECT_EQ(a.quality.snr_db, b.quality.snr_db);
    EXPECT_EQ(a.quality.settled_after_s, b.quality.settled_after_s);
    EXPECT_EQ(a.quality.analysed_duration_s, b.quality.analysed_duration_s);
    EXPECT_EQ(a.quality.settling, b.quality.settling);
    EXPECT_EQ(a.quality.warnings, b.quality.warnings);
    EXPECT_EQ(a.quality.unsettled, b.quality.unsettled);
    EXPECT_EQ(a.quality.unsettled_change_relative, b.quality.unsettled_change_relative);
    EXPECT_EQ(a.quality.unsettled_channel, b.quality.unsettled_channel);
    ExpectSameChannel(a.force, b.force);
    ASSERT_EQ(b.responses.size(), 2u);
    for (std::size_t c = 0; c < 2; ++c) ExpectSameChannel(a.responses[c], b.responses[c]);
  }
  EXPECT_NE(back.steps[1].Find("acc2"), nullptr);
  EXPECT_EQ(back.steps[1].Find("acc9"), nullptr);
}

TEST(PhasorSetIoTest, JsonHoldsAmplitudePhaseAndConvention) {
  const std::string json = PhasorSetToJson(Example());
  for (const char* key : {"\"format\": \"beamid-phasors/1\"", "\"convention\"", "\"amplitude\"", "\"phase_rad\"",
                          "\"std_amplitude\"", "\"std_phase_rad\"", "\"unit\": \"m/s^2\"", "\"role\": \"excitation\""})
    EXPECT_NE(json.find(key), std::string::npos) << key;
}

TEST(PhasorSetIoTest, CsvHasOneRowPerStepChannelAndHarmonic) {
  const std::string csv = PhasorSetToCsv(Example());
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 1 + 2 * 3 * 2);
  EXPECT_EQ(csv.rfind("file,level,nominal_frequency_Hz,frequency_Hz,", 0), 0u);
  EXPECT_NE(csv.find("\nlow/step_001.csv,low,50.25,"), std::string::npos);
  const std::size_t header_fields = static_cast<std::size_t>(std::count(csv.begin(), csv.begin() + static_cast<std::ptrdiff_t>(csv.find('\n')), ','));
  const std::size_t last_line = csv.rfind('\n', csv.size() - 2) + 1;
  EXPECT_EQ(static_cast<std::size_t>(std::count(csv.begin() + static_cast<std::ptrdiff_t>(last_line), csv.end(), ',')), header_fields);
}

// A file of a beamid older than the campaign's content hash reads, with no
// hash: the commands refuse it against a campaign (signal/campaign_identity.h).
TEST(PhasorSetIoTest, AFileWithoutTheCampaignHashReadsWithNone) {
  nlohmann::json json = nlohmann::json::parse(PhasorSetToJson(Example()));
  ASSERT_TRUE(json.contains("campaign_sha256"));
  json.erase("campaign_sha256");
  const PhasorSet back = PhasorSetFromJson(json.dump(), "old.json");
  EXPECT_EQ(back.campaign_sha256, "");
  EXPECT_EQ(back.campaign, "io test");
}

TEST(PhasorSetIoTest, BadFilesNameTheFile) {
  EXPECT_THROW(ReadPhasorSetJson("/nonexistent/phasors.json"), InputError);
  try {
    PhasorSetFromJson(R"({"format": "stepped-sine-campaign/1"})", "some.json");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "some.json");
    EXPECT_NE(std::string(e.what()).find(R"(field "format" is "stepped-sine-campaign/1", not "beamid-phasors/1")"), std::string::npos) << e.what();
  }
  try {
    PhasorSetFromJson(R"({"format": "beamid-phasors/1", "campaign": "x"})", "other.json");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(R"(other.json: field "num_harmonics" is missing)"), std::string::npos) << e.what();
  }
}

// The declaration's generic checks (tests/support/schema_checks.h) on a
// file that holds every optional field: notes, an unsettled step, a
// skipped step.
TEST(PhasorSetIoTest, TheDeclarationHolds) {
  PhasorSet set = Example();
  for (StepPhasors& step : set.steps) {
    step.quality.notes = {"a note"};
    step.quality.unsettled = true;
    step.quality.unsettled_change_relative = 0.02;
    step.quality.unsettled_channel = "acc1";
  }
  set.skipped.push_back({.file = "low/step_009.csv", .level = "low", .nominal_frequency_hz = 52.0, .reason = "clipped"});
  beamid::testing::ExpectDeclarationHolds({
      .fields = PhasorSetFields(),
      .sample = PhasorSetToJson(set),
      .read = [](const std::string& text) { PhasorSetFromJson(text, "p.json"); },
      .rewrite = [](const std::string& text) { return PhasorSetToJson(PhasorSetFromJson(text, "p.json")); },
  });
}

// The force comes first, every response after it: a file that lists them
// otherwise names the rule and the list.
TEST(PhasorSetIoTest, AResponseListedBeforeTheForceIsRefused) {
  nlohmann::ordered_json json = nlohmann::ordered_json::parse(PhasorSetToJson(Example()));
  auto& channels = json["steps"][1]["channels"];
  std::swap(channels[0], channels[1]);
  try {
    PhasorSetFromJson(json.dump(1), "p.json");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "p.json");
    EXPECT_NE(std::string(e.what()).find(R"(field "steps[1].channels" breaks the rule: the excitation channel comes first)"),
              std::string::npos)
        << e.what();
  }
  // A harmonic beyond num_harmonics.
  json = nlohmann::ordered_json::parse(PhasorSetToJson(Example()));
  json["steps"][0]["channels"][2]["harmonics"][1]["k"] = 3;
  try {
    PhasorSetFromJson(json.dump(1), "p.json");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(R"(field "steps[0].channels[2].harmonics[1].k" breaks the rule)"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace beamid::signal
