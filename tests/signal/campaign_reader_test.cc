// Campaign and recording reader: unit conversion, column order, and one test
// per bad input of the format, each checking that the error names the file,
// the channel and a fix.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <string>

#include <unistd.h>

#include <gtest/gtest.h>

#include "signal/campaign.h"
#include "signal/input_error.h"
#include "signal/phasor_estimator.h"
#include "signal/phasor_set_io.h"
#include "signal/recording.h"
#include "tests/support/schema_checks.h"

namespace beamid::signal {
namespace {

namespace fs = std::filesystem;

constexpr double kRateHz = 1000.0;
constexpr double kFrequencyHz = 50.0;

std::string CampaignJson(const std::string& acc_unit = "g", const std::string& extra_step_key = "") {
  return R"({
  "format": "stepped-sine-campaign/1",
  "name": "reader test",
  "beam": {"length_m": 0.6, "width_m": 0.04, "thickness_m": 0.005, "youngs_modulus_Pa": 2.1e11, "density_kg_m3": 7850},
  "excitation": {"channel": "force", "position_m": 0.57, "quantity": "force", "unit": "N"},
  "sensors": [
    {"channel": "acc1", "position_m": 0.1, "quantity": "acceleration", "unit": ")" +
         acc_unit + R"("},
    {"channel": "vel2", "position_m": 0.3, "quantity": "velocity", "unit": "mm/s", "mass_kg": 0.004}
  ],
  "steps": [{"file": "step_000.csv", "frequency_Hz": 50.0, "level": "low")" +
         extra_step_key + R"(}]
})";
}

// Force = sin, acc1 (in g) = 2 cos, vel2 (in mm/s) = 300 sin(2·), columns in
// a different order than campaign.json.
// vel2_step_mm_s > 0: vel2 is a quiet signal (0.6 of a step in amplitude)
// read by a converter of that resolution.
std::string RecordingCsv(int num_samples = 1000, double acc_clip_g = 1e9, double vel2_step_mm_s = 0.0) {
  std::string csv = "acc1,time_s, vel2 ,force\n";
  char line[160];
  for (int n = 0; n < num_samples; ++n) {
    const double t = n / kRateHz;
    const double phase = 2.0 * std::numbers::pi * kFrequencyHz * t;
    std::snprintf(line, sizeof line, "%.9f,%.7f,%.6f,%.9f\r\n", std::clamp(2.0 * std::cos(phase), -acc_clip_g, acc_clip_g), t, vel2_step_mm_s > 0.0 ? vel2_step_mm_s * std::round(0.6 * std::sin(phase)) : 300.0 * std::sin(2 * phase),
                  std::sin(phase) + 0.1);
    csv += line;
  }
  return csv;
}

class CampaignReaderTest : public ::testing::Test {
 protected:
  void SetUp() override {
    folder_ = fs::temp_directory_path() /
              ("beamid_reader_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()) + "_" +
               std::to_string(::getpid()));
    fs::remove_all(folder_);
    fs::create_directories(folder_);
    Write("campaign.json", CampaignJson());
    Write("step_000.csv", RecordingCsv());
  }
  void TearDown() override { fs::remove_all(folder_); }

  void Write(const std::string& name, const std::string& text) { std::ofstream(folder_ / name) << text; }

  // Reads the campaign and its one recording; returns the InputError thrown.
  InputError ExpectError() {
    try {
      Campaign campaign = ReadCampaign(folder_);
      ReadRecording(campaign, campaign.steps.front());
    } catch (const InputError& e) {
      return e;
    }
    ADD_FAILURE() << "no InputError thrown";
    return InputError("", "", "", "");
  }

  // Replaces sample rows [first, last) of the recording by a transform of
  // their values (column index as in the CSV: acc1, time_s, vel2, force).
  void EditRecording(int first, int last, int column, const std::string& value) {
    std::string csv = RecordingCsv();
    std::string out;
    std::size_t pos = 0;
    int row = -1;
    while (pos < csv.size()) {
      std::size_t eol = csv.find('\n', pos);
      std::string line = csv.substr(pos, eol - pos + 1);
      if (row >= first && row < last) {
        std::vector<std::string> fields;
        std::size_t p = 0, q;
        while ((q = line.find(',', p)) != std::string::npos) {
          fields.push_back(line.substr(p, q - p));
          p = q + 1;
        }
        fields.push_back(line.substr(p, line.size() - p - 2));
        fields[static_cast<std::size_t>(column)] = value;
        line.clear();
        for (std::size_t i = 0; i < fields.size(); ++i) line += (i ? "," : "") + fields[i];
        line += "\n";
      }
      out += line;
      pos = eol + 1;
      ++row;
    }
    Write("step_000.csv", out);
  }

  std::string StepFile() const { return (folder_ / "step_000.csv").string(); }
  std::string CampaignFile() const { return (folder_ / "campaign.json").string(); }

  fs::path folder_;
};

// The error's message names the file, the channel and gives a fix.
void ExpectNames(const InputError& e, const std::string& file, const std::string& channel, const std::string& problem) {
  const std::string message = e.what();
  EXPECT_EQ(e.file(), file) << message;
  EXPECT_EQ(e.channel(), channel) << message;
  EXPECT_NE(message.find(file), std::string::npos) << message;
  if (!channel.empty()) {
    EXPECT_NE(message.find("'" + channel + "'"), std::string::npos) << message;
  }
  EXPECT_NE(message.find(problem), std::string::npos) << message;
  EXPECT_NE(message.find("Fix: "), std::string::npos) << message;
}

TEST_F(CampaignReaderTest, ReadsCampaignAndConvertsUnitsToSi) {
  Campaign campaign = ReadCampaign(folder_);
  EXPECT_EQ(campaign.name, "reader test");
  EXPECT_DOUBLE_EQ(campaign.beam.youngs_modulus_Pa, 2.1e11);
  ASSERT_EQ(campaign.sensors.size(), 2u);
  EXPECT_EQ(campaign.sensors[0].quantity, Quantity::kAcceleration);
  EXPECT_EQ(campaign.sensors[1].mass_kg.value_or(-1.0), 0.004);
  EXPECT_FALSE(campaign.sensors[0].mass_kg.has_value());
  ASSERT_EQ(campaign.steps.size(), 1u);
  EXPECT_DOUBLE_EQ(campaign.steps[0].frequency_hz, 50.0);

  Recording recording = ReadRecording(campaign, campaign.steps[0]);
  ASSERT_EQ(recording.channels, (std::vector<std::string>{"force", "acc1", "vel2"}));
  EXPECT_EQ(recording.NumSamples(), 1000);
  EXPECT_NEAR(recording.sample_rate_hz, kRateHz, 1e-6);
  for (int n : {0, 3, 517, 999}) {
    const double phase = 2.0 * std::numbers::pi * kFrequencyHz * n / kRateHz;
    EXPECT_NEAR(recording.samples(n, 0), std::sin(phase) + 0.1, 1e-9);
    EXPECT_NEAR(recording.samples(n, 1), 2.0 * 9.80665 * std::cos(phase), 1e-8);  // g -> m/s^2
    EXPECT_NEAR(recording.samples(n, 2), 0.3 * std::sin(2 * phase), 1e-9);        // mm/s -> m/s
  }
}

TEST_F(CampaignReaderTest, MissingCampaignJson) {
  fs::remove(folder_ / "campaign.json");
  ExpectNames(ExpectError(), CampaignFile(), "", "cannot read the campaign description (no such file)");
}

TEST_F(CampaignReaderTest, InvalidJson) {
  Write("campaign.json", "{\"format\": ");
  ExpectNames(ExpectError(), CampaignFile(), "", "not valid JSON");
}

TEST_F(CampaignReaderTest, WrongFormatString) {
  std::string json = CampaignJson();
  json.replace(json.find("campaign/1"), 10, "campaign/2");
  Write("campaign.json", json);
  ExpectNames(ExpectError(), CampaignFile(), "", "stepped-sine-campaign/2");
}

TEST_F(CampaignReaderTest, UnknownUnitNamesChannelAndAcceptedUnits) {
  Write("campaign.json", CampaignJson("ft/s^2"));
  InputError e = ExpectError();
  ExpectNames(e, CampaignFile(), "acc1", "unit 'ft/s^2'");
  EXPECT_NE(std::string(e.what()).find("m/s^2, g"), std::string::npos) << e.what();
}

TEST_F(CampaignReaderTest, UnitOfWrongQuantity) {
  Write("campaign.json", CampaignJson("mm"));
  ExpectNames(ExpectError(), CampaignFile(), "acc1", "not accepted for a acceleration");
}

TEST_F(CampaignReaderTest, UnknownKeyIsReportedWithAcceptedKeys) {
  Write("campaign.json", CampaignJson("g", R"(, "frequncy": 3)"));
  InputError e = ExpectError();
  ExpectNames(e, CampaignFile(), "", R"(field "steps[0].frequncy" is not a field here)");
  EXPECT_NE(std::string(e.what()).find("frequency_Hz"), std::string::npos);
}

TEST_F(CampaignReaderTest, NonPhysicalBeamValue) {
  std::string json = CampaignJson();
  json.replace(json.find("\"density_kg_m3\": 7850"), 21, "\"density_kg_m3\": -1");
  Write("campaign.json", json);
  ExpectNames(ExpectError(), CampaignFile(), "", R"(field "beam.density_kg_m3" = -1 lies outside 1 .. 100000)");
}

// A typing error such as 1e300 m is refused with the stated range, before
// it can reach a solver as a number (it used to end as "no start converged").
TEST_F(CampaignReaderTest, BeamOutsideTheRangeOfABeamTest) {
  std::string json = CampaignJson();
  json.replace(json.find("\"length_m\": 0.6"), 15, "\"length_m\": 1e300");
  Write("campaign.json", json);
  ExpectNames(ExpectError(), CampaignFile(), "", R"(field "beam.length_m" = 1e+300 lies outside 0.001 .. 100)");
  // A width beyond the length is a beam test's rule, between two fields.
  json = CampaignJson();
  json.replace(json.find("\"width_m\": 0.04"), 15, "\"width_m\": 0.9");
  Write("campaign.json", json);
  ExpectNames(ExpectError(), CampaignFile(), "", "beam: width_m = 0.900000 is not a beam test's (1 µm to the length)");
}

TEST_F(CampaignReaderTest, AFolderInPlaceOfCampaignJsonIsNamed) {
  fs::remove(folder_ / "campaign.json");
  fs::create_directories(folder_ / "campaign.json");
  ExpectNames(ExpectError(), CampaignFile(), "", "it is a folder, not a file");
}

// One corrupted sample of 1000× the force level would shift every harmonic
// of the step; it is named with its time instead of being averaged in.
TEST_F(CampaignReaderTest, ASpikeIsNamedWithItsTime) {
  EditRecording(500, 501, 3, "900");
  ExpectNames(ExpectError(), StepFile(), "force", "spike: the sample at t = 0.5 s (900)");
}

TEST_F(CampaignReaderTest, MissingRecordingFile) {
  fs::remove(folder_ / "step_000.csv");
  InputError e = ExpectError();
  ExpectNames(e, StepFile(), "", "steps[0] is missing");
}

TEST_F(CampaignReaderTest, UnknownColumnInRecording) {
  std::string csv = RecordingCsv();
  csv.replace(0, 4, "acc9");
  Write("step_000.csv", csv);
  // A column no channel uses is ignored; the channel it replaced is missing.
  ExpectNames(ExpectError(), StepFile(), "acc1", "missing from the header (columns no channel uses: 'acc9')");
}

TEST_F(CampaignReaderTest, ChannelMissingFromRecording) {
  std::string csv = RecordingCsv();
  csv.replace(csv.find("vel2"), 4, "time");
  Write("step_000.csv", csv);
  // "time" is a time column without a unit: the reader stops there.
  ExpectNames(ExpectError(), StepFile(), "time", "the time column has no unit");
  std::string json = CampaignJson();
  json.replace(json.find("\"vel2\""), 6, "\"vel3\"");
  Write("campaign.json", json);
  Write("step_000.csv", RecordingCsv());
  ExpectNames(ExpectError(), StepFile(), "vel3", "missing from the header (columns no channel uses: 'vel2')");
}

TEST_F(CampaignReaderTest, CampaignChannelWithoutColumn) {
  std::string csv = "acc1,time_s,force\n";
  for (int n = 0; n < 1000; ++n) csv += std::to_string(std::sin(n)) + "," + std::to_string(n / kRateHz) + ",1\n";
  Write("step_000.csv", csv);
  ExpectNames(ExpectError(), StepFile(), "vel2", "missing from the header");
}

TEST_F(CampaignReaderTest, NaNSample) {
  EditRecording(412, 413, 2, "nan");
  ExpectNames(ExpectError(), StepFile(), "vel2", "NaN or infinite value at line 414");
}

// One corrupted sample of 1e308 was accepted and gave h1 = 7e304 with a
// null standard deviation.
TEST_F(CampaignReaderTest, SampleBeyondAnyMeasurement) {
  EditRecording(412, 413, 0, "1e308");
  ExpectNames(ExpectError(), StepFile(), "acc1", "value 1e308 at line 414 is beyond any measurement");
}

TEST_F(CampaignReaderTest, UnreadableNumber) {
  EditRecording(20, 21, 0, "1,5");
  InputError e = ExpectError();
  EXPECT_EQ(e.file(), StepFile());
  EXPECT_NE(std::string(e.what()).find("line 22"), std::string::npos) << e.what();
  EditRecording(20, 21, 3, "0.5V");
  ExpectNames(ExpectError(), StepFile(), "force",
              "the file uses ',' as separator and '.' as decimal mark: line 22, column force: '0.5V' is not a number");
}

TEST_F(CampaignReaderTest, NonIncreasingTime) {
  EditRecording(100, 101, 1, "0.0985");
  ExpectNames(ExpectError(), StepFile(), "time_s", "time does not increase at line 102");
}

TEST_F(CampaignReaderTest, NonUniformTime) {
  // A missing sample: the time stamps after row 500 jump by two periods.
  std::string csv = RecordingCsv();
  std::size_t row500 = 0;
  for (int i = 0; i < 501; ++i) row500 = csv.find('\n', row500) + 1;
  std::size_t row501 = csv.find('\n', row500) + 1;
  csv.erase(row500, row501 - row500);
  Write("step_000.csv", csv);
  ExpectNames(ExpectError(), StepFile(), "time_s", "non-uniform sampling at line");
}

TEST_F(CampaignReaderTest, TooShortRecord) {
  Write("step_000.csv", RecordingCsv(150));  // 7.5 periods of 50 Hz
  ExpectNames(ExpectError(), StepFile(), "", "too short");
}

TEST_F(CampaignReaderTest, ClippedChannel) {
  // acc1 = 2 cos through an amplifier that saturates at 1.5 g: every peak
  // is flat over 4-5 samples.
  Write("step_000.csv", RecordingCsv(1000, 1.5));
  ExpectNames(ExpectError(), StepFile(), "acc1", "clipped: ");
}

TEST_F(CampaignReaderTest, Dropout) {
  EditRecording(600, 610, 3, "0");
  ExpectNames(ExpectError(), StepFile(), "force", "dropout: 10 identical samples (0) from t = 0.6 s");
}

TEST_F(CampaignReaderTest, AQuietQuantisedChannelIsNoDropout) {
  // vel2 spans two converter steps: zero for 7 samples in a row, then an
  // extreme for 3. Those runs are the converter's resolution, not a dropout
  // or clipping, and the recording is read.
  Write("step_000.csv", RecordingCsv(1000, 1e9, 0.001));
  const Campaign campaign = ReadCampaign(folder_);
  const Recording recording = ReadRecording(campaign, campaign.steps.front());
  EXPECT_EQ(recording.samples.rows(), 1000);
  // The same runs on a channel that spans many steps are a dropout.
  RecordingChecks strict;
  strict.min_converter_steps_for_runs = 0.0;
  try {
    ReadRecording(campaign, campaign.steps.front(), strict);
    ADD_FAILURE() << "no InputError thrown";
  } catch (const InputError& e) {
    EXPECT_EQ(e.channel(), "vel2");
    EXPECT_NE(std::string(e.what()).find("identical samples"), std::string::npos) << e.what();
  }
}

TEST_F(CampaignReaderTest, DisconnectedChannel) {
  EditRecording(0, 1000, 2, "0");
  ExpectNames(ExpectError(), StepFile(), "vel2", "constant");
}

TEST_F(CampaignReaderTest, WrongNumberOfValues) {
  EditRecording(30, 31, 2, "1,2");
  ExpectNames(ExpectError(), StepFile(), "force", "line 32 does not have one value per header column");
}

TEST_F(CampaignReaderTest, SampleRateDisagreesWithCampaign) {
  std::string json = CampaignJson();
  json.insert(json.rfind('}'), ", \"sample_rate_Hz\": 1024");
  Write("campaign.json", json);
  ExpectNames(ExpectError(), StepFile(), "time_s", "sample_rate_Hz = 1024");
}

TEST(QuantityTest, UnitFactorsAndNames) {
  EXPECT_EQ(UnitToSiFactor(Quantity::kAcceleration, "g").value(), 9.80665);
  EXPECT_EQ(UnitToSiFactor(Quantity::kDisplacement, "mm").value(), 1e-3);
  EXPECT_FALSE(UnitToSiFactor(Quantity::kVelocity, "m").has_value());
  EXPECT_EQ(ParseQuantity("velocity"), Quantity::kVelocity);
  EXPECT_FALSE(ParseQuantity("jerk").has_value());
  EXPECT_EQ(SiUnit(Quantity::kAcceleration), "m/s^2");
  EXPECT_EQ(DerivativeOrder(Quantity::kAcceleration), 2);
  EXPECT_THROW(DerivativeOrder(Quantity::kForce), std::invalid_argument);
}

// A campaign names its recordings relative to its folder; one that reaches
// outside (../, an absolute path, a link out) would make beamid read, and
// quote in its errors, any file on the machine.
TEST_F(CampaignReaderTest, RefusesARecordingOutsideTheCampaignFolder) {
  for (const std::string file : {"../../../../etc/passwd", "/etc/passwd", "link_out.csv"}) {
    fs::remove(folder_ / "link_out.csv");
    fs::create_symlink("/etc/hostname", folder_ / "link_out.csv");
    std::string json = CampaignJson();
    json.replace(json.find("step_000.csv"), 12, file);
    Write("campaign.json", json);
    const InputError e = ExpectError();
    ExpectNames(e, CampaignFile(), "", "lies outside the campaign folder");
    EXPECT_EQ(std::string(e.what()).find("root:"), std::string::npos) << "no line of the file is quoted";
  }
}

TEST_F(CampaignReaderTest, RefusesTwoStepsThatShareARecording) {
  std::string json = CampaignJson();
  const std::string step = R"({"file": "step_000.csv", "frequency_Hz": 50.0, "level": "low"})";
  json.replace(json.find(step), step.size(), step + ", " + R"({"file": "./step_000.csv", "frequency_Hz": 51.0, "level": "low"})");
  Write("campaign.json", json);
  ExpectNames(ExpectError(), CampaignFile(), "", "is named by another step too");
}

TEST_F(CampaignReaderTest, RefusesAKeyWrittenTwiceAndANumberBeyondRange) {
  std::string json = CampaignJson();
  json.replace(json.find(R"("name": "reader test",)"), 22, R"("name": "a", "name": "b",)");
  Write("campaign.json", json);
  ExpectNames(ExpectError(), CampaignFile(), "", "\"name\" is written twice");
  json = CampaignJson();
  json.replace(json.find("2.1e11"), 6, "1e400");
  Write("campaign.json", json);
  ExpectNames(ExpectError(), CampaignFile(), "", "not valid JSON");
}

// The excitation's line of CampaignJson() replaced by `excitation`.
std::string WithExcitation(const std::string& excitation) {
  std::string json = CampaignJson();
  const std::string force = R"({"channel": "force", "position_m": 0.57, "quantity": "force", "unit": "N"})";
  json.replace(json.find(force), force.size(), excitation);
  return json;
}

TEST_F(CampaignReaderTest, AVoltageOrBaseAccelerationExcitationIsReadWithItsUnit) {
  Write("campaign.json",
        WithExcitation(
            R"({"channel": "force", "position_m": 0.57, "quantity": "voltage", "unit": "mV", "sensitivity_N_per_V": 12.5})"));
  Campaign campaign = ReadCampaign(folder_);
  EXPECT_EQ(campaign.excitation.quantity, Quantity::kVoltage);
  EXPECT_EQ(campaign.excitation.to_si_factor, 1e-3);
  EXPECT_EQ(campaign.excitation.sensitivity_N_per_V, 12.5);
  // The model-free chain takes it: phasors per volt, labelled as such.
  const Recording recording = ReadRecording(campaign, campaign.steps.front());
  const StepPhasors step = EstimateStepPhasors(recording, campaign, campaign.steps.front());
  EXPECT_EQ(step.force.quantity, Quantity::kVoltage);
  PhasorSet set;
  set.num_harmonics = 5;
  set.steps.push_back(step);
  EXPECT_NE(PhasorSetToJson(set).find(R"("quantity": "voltage")"), std::string::npos);
  EXPECT_NE(PhasorSetToJson(set).find(R"("unit": "V")"), std::string::npos);

  Write("campaign.json",
        WithExcitation(R"({"channel": "force", "position_m": 0.0, "quantity": "base_acceleration", "unit": "g"})"));
  campaign = ReadCampaign(folder_);
  EXPECT_EQ(campaign.excitation.quantity, Quantity::kBaseAcceleration);
  EXPECT_EQ(campaign.excitation.to_si_factor, 9.80665);
  EXPECT_EQ(DerivativeOrder(Quantity::kBaseAcceleration), 2);
  EXPECT_THROW(DerivativeOrder(Quantity::kVoltage), std::invalid_argument);
}

TEST_F(CampaignReaderTest, AnExcitationQuantityOrSensitivityThatMakesNoSenseIsRefused) {
  Write("campaign.json", WithExcitation(R"({"channel": "force", "position_m": 0.57, "quantity": "acceleration", "unit": "g"})"));
  ExpectNames(ExpectError(), CampaignFile(), "force", "the excitation quantity is 'acceleration'");
  Write("campaign.json",
        WithExcitation(R"({"channel": "force", "position_m": 0.57, "quantity": "force", "unit": "N", "sensitivity_N_per_V": 3})"));
  ExpectNames(ExpectError(), CampaignFile(), "force", "'sensitivity_N_per_V' is given for a force excitation");
  Write("campaign.json", WithExcitation(R"({"channel": "force", "position_m": 0.57, "quantity": "voltage", "unit": "N"})"));
  ExpectNames(ExpectError(), CampaignFile(), "force", "unit 'N' is not accepted for a voltage");
  Write("campaign.json",
        WithExcitation(R"({"channel": "force", "position_m": 0.57, "quantity": "voltage", "unit": "V", "sensitivity_N_per_V": -2})"));
  ExpectNames(ExpectError(), CampaignFile(), "force", R"(field "excitation.sensitivity_N_per_V" = -2 lies outside > 0)");
}

// The declaration's generic checks (tests/support/schema_checks.h) on a
// campaign.json written by the simulator's writer (hb/campaign_file.h)
// with every optional field, read by the reader of the commands.
TEST(CampaignFileTest, TheDeclarationHolds) {
  hb::CampaignFile file{.name = "declaration",
                        .excitation = {.channel = "drive", .position_m = 0.57, .quantity = "voltage", .unit = "mV",
                                       .sensitivity_N_per_V = 12.5},
                        .steps = {{.file = "low/step_000.csv", .frequency_hz = 50.0, .level = "low"}},
                        .sample_rate_hz = 5120.0,
                        .ignore_channels = {"acc2"},
                        .recording_layout = hb::CampaignRecordingLayout{.lines_before_header = 3, .units_row = true}};
  file.sensors.push_back({.channel = "acc1", .position_m = 0.1, .quantity = "acceleration", .unit = "g",
                          .mass_kg = 0.004, .column = "Ch2 acc1 [g]"});
  file.sensors.push_back({.channel = "acc2", .position_m = 0.3, .quantity = "acceleration", .unit = "m/s^2",
                          .column_number = 4});
  beamid::testing::ExpectDeclarationHolds({
      .fields = hb::CampaignFileFields(),
      .sample = hb::CampaignFileToJson(file),
      .read = [](const std::string& text) { ParseCampaign(text, "folder", "folder/campaign.json"); },
      .rewrite =
          [](const std::string& text) {
            return hb::CampaignFileToJson(hb::CampaignFileFromJson(text, "folder/campaign.json"));
          },
  });
}

// A range complaint about a channel's field names the channel, as the
// engineer knows it, besides the field's path.
TEST_F(CampaignReaderTest, ARangeComplaintInASensorNamesItsChannel) {
  std::string json = CampaignJson();
  json.replace(json.find("\"mass_kg\": 0.004"), 16, "\"mass_kg\": -1");
  Write("campaign.json", json);
  ExpectNames(ExpectError(), CampaignFile(), "vel2", R"(field "sensors[1].mass_kg" = -1 lies outside ≥ 0)");
}

}  // namespace
}  // namespace beamid::signal
