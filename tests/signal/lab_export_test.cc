// Recordings as acquisition software exports them, read without editing
// (signal/recording.h, signal/table_reader.h, docs/campaign-format.md): a
// drive in V or mV, channels mapped to their columns by header text or
// number, a metadata block before the header and a units row under it. Each
// export reads to the samples of the same data written the plain way (time_s
// and the channel names as headers), and each way of getting the layout
// wrong is an InputError naming the file, the channel and the fix.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <gtest/gtest.h>

#include "signal/campaign.h"
#include "signal/input_error.h"
#include "signal/recording.h"
#include "signal/table_reader.h"
#include "tests/signal/synthetic_signal.h"
#include "tests/support/expect_refused.h"
#include "tests/support/temp_path.h"

namespace beamid::signal {
namespace {

namespace fs = std::filesystem;
using beamid::testing::InputErrorOf;

constexpr double kRateHz = 5120.0;
constexpr int kSamples = 2048;
constexpr double kFrequencyHz = 40.0;

// A drive [V], an acceleration [g] and a velocity [mm/s]: tones with a
// little noise, as a step records them.
std::vector<Eigen::VectorXd> PlainColumns() {
  std::mt19937 rng(5);
  std::normal_distribution<double> normal;
  std::vector<Eigen::VectorXd> columns;
  Eigen::VectorXd time(kSamples);
  for (int n = 0; n < kSamples; ++n) time[n] = n / kRateHz;
  columns.push_back(time);
  for (int c = 0; c < 3; ++c) {
    testing::Tone tone = testing::RandomTone(rng, 3, kFrequencyHz, 0.5 + c);
    tone.sample_rate_hz = kRateHz;
    Eigen::VectorXd x = testing::Synthesize(tone, kSamples);
    for (int n = 0; n < kSamples; ++n) x[n] += 1e-3 * normal(rng);
    columns.push_back(x);
  }
  return columns;
}

// The lines of a table: the header, then one row per sample of `columns`
// (in the header's order).
std::string Table(const std::vector<std::string>& header, const std::vector<Eigen::VectorXd>& columns,
                  const std::string& before_header = "", const std::string& units_row = "") {
  std::string text = before_header;
  for (std::size_t i = 0; i < header.size(); ++i) text += (i ? "," : "") + header[i];
  text += "\n" + units_row;
  char buffer[64];
  for (int n = 0; n < kSamples; ++n) {
    for (std::size_t i = 0; i < columns.size(); ++i) {
      std::snprintf(buffer, sizeof buffer, i == 0 ? "%.10f" : "%.12g", columns[i][n]);
      text += (i ? "," : "") + std::string(buffer);
    }
    text += "\n";
  }
  return text;
}

std::string Channel(const std::string& name, const std::string& quantity, const std::string& unit,
                    const std::string& mapping = "") {
  return R"({"channel": ")" + name + R"(", "position_m": 0.3, "quantity": ")" + quantity + R"(", "unit": ")" + unit +
         "\"" + (mapping.empty() ? "" : ", " + mapping) + "}";
}

struct Channels {
  std::string drive = Channel("drive", "voltage", "V");
  std::string acc1 = Channel("acc1", "acceleration", "g");
  std::string vel2 = Channel("vel2", "velocity", "mm/s");
  std::string layout;  // the "recording_layout" object, "" for none
};

std::string CampaignJson(const Channels& c) {
  return R"({"format": "stepped-sine-campaign/1",
  "beam": {"length_m": 0.6, "width_m": 0.04, "thickness_m": 0.005, "youngs_modulus_Pa": 2.1e11, "density_kg_m3": 7850},
  "excitation": )" + c.drive + R"(,
  "sensors": [)" + c.acc1 + ", " + c.vel2 + R"(],
  "steps": [{"file": "step.csv", "frequency_Hz": 40.0, "level": "low"}])" +
         (c.layout.empty() ? "" : ",\n  \"recording_layout\": " + c.layout) + "}";
}

class LabExportTest : public ::testing::Test {
 protected:
  void SetUp() override {
    folder_ = beamid::testing::UniqueTempPath("beamid_lab_export");
    fs::remove_all(folder_);
    fs::create_directories(folder_);
  }
  void TearDown() override { fs::remove_all(folder_); }

  Recording Read(const Channels& channels, const std::string& csv) {
    std::ofstream(folder_ / "campaign.json") << CampaignJson(channels);
    std::ofstream(folder_ / "step.csv", std::ios::binary) << csv;
    campaign_ = ReadCampaign(folder_);
    return ReadRecording(campaign_, campaign_.steps.front());
  }
  // The plain export: time_s and the channel names, campaign.json's units.
  Recording Plain() { return Read({}, Table({"time_s", "drive", "acc1", "vel2"}, columns_)); }
  InputError Error(const Channels& channels, const std::string& csv) {
    try {
      Read(channels, csv);
    } catch (const InputError& e) {
      return e;
    }
    ADD_FAILURE() << "no InputError";
    return InputError("", "", "", "");
  }
  void ExpectNames(const InputError& e, const std::string& channel, const std::string& problem) const {
    const std::string message = e.what();
    EXPECT_EQ(e.file(), (folder_ / "step.csv").string()) << message;
    EXPECT_EQ(e.channel(), channel) << message;
    EXPECT_NE(message.find(problem), std::string::npos) << message;
    EXPECT_NE(message.find("Fix: "), std::string::npos) << message;
  }

  fs::path folder_;
  Campaign campaign_;
  const std::vector<Eigen::VectorXd> columns_ = PlainColumns();
};

// The same samples in SI, to the printed digits.
void ExpectSameRecording(const Recording& read, const Recording& plain) {
  EXPECT_EQ(read.channels, plain.channels);
  ASSERT_EQ(read.samples.rows(), plain.samples.rows());
  ASSERT_EQ(read.samples.cols(), plain.samples.cols());
  EXPECT_NEAR(read.sample_rate_hz, plain.sample_rate_hz, 1e-9);
  for (Eigen::Index c = 0; c < plain.samples.cols(); ++c)
    EXPECT_LE((read.samples.col(c) - plain.samples.col(c)).cwiseAbs().maxCoeff(),
              1e-10 * plain.samples.col(c).cwiseAbs().maxCoeff())
        << plain.channels[static_cast<std::size_t>(c)];
}

std::vector<Eigen::VectorXd> Scaled(std::vector<Eigen::VectorXd> columns, std::size_t column, double factor) {
  columns[column] *= factor;
  return columns;
}

TEST(LabExportUnitsTest, VoltsAndMillivoltsAreUnitsOfVoltage) {
  EXPECT_EQ(NormaliseUnit("V"), "V");
  EXPECT_EQ(NormaliseUnit("volts"), "V");
  EXPECT_EQ(NormaliseUnit("mV"), "mV");
  EXPECT_EQ(NormaliseUnit(" millivolt "), "mV");
  EXPECT_EQ(UnitToSiFactor(Quantity::kVoltage, *NormaliseUnit("mV")), 1e-3);
}

TEST_F(LabExportTest, ADriveInVoltsOrMillivoltsReadsToVolts) {
  const Recording plain = Plain();
  ExpectSameRecording(Read({}, Table({"time [s]", "drive [V]", "acc1 [g]", "vel2"}, columns_)), plain);
  Channels millivolts;
  millivolts.drive = Channel("drive", "voltage", "mV");
  const Recording read = Read(millivolts, Table({"time_s", "drive [mV]", "acc1", "vel2"}, Scaled(columns_, 1, 1e3)));
  ExpectSameRecording(read, plain);
  // A header in mV where campaign.json says V is a contradiction, not an unknown unit.
  ExpectNames(Error({}, Table({"time_s", "drive [mV]", "acc1", "vel2"}, columns_)), "drive",
              "the header gives the unit 'mV' but campaign.json declares 'V'");
}

TEST_F(LabExportTest, ChannelsMappedToTheirColumnsReadTheSameNumbers) {
  const Recording plain = Plain();
  // The software's own headers, in its order, the laser in m/s.
  Channels by_text;
  by_text.drive = Channel("drive", "voltage", "V", R"("column": "Ch1 Drive [V]")");
  by_text.acc1 = Channel("acc1", "acceleration", "g", R"("column": "Ch2 acc1 [g]")");
  by_text.vel2 = Channel("vel2", "velocity", "m/s", R"x("column": "Laser (M - Filtered)")x");
  const std::vector<Eigen::VectorXd> reordered = {columns_[0], Scaled(columns_, 3, 1e-3)[3], columns_[1], columns_[2]};
  const std::string export_text =
      Table({"Time [s]", "Laser (M - Filtered) [m/s]", "Ch1 Drive [V]", "Ch2 acc1 [g]"}, reordered);
  Recording read = Read(by_text, export_text);
  // Converted to SI from m/s where the plain file has mm/s.
  ExpectSameRecording(read, plain);
  EXPECT_TRUE(read.ignored_columns.empty());

  Channels by_number;
  by_number.drive = Channel("drive", "voltage", "V", R"("column_number": 3)");
  by_number.acc1 = Channel("acc1", "acceleration", "g", R"("column_number": 4)");
  by_number.vel2 = Channel("vel2", "velocity", "m/s", R"("column_number": 2)");
  ExpectSameRecording(Read(by_number, export_text), plain);
}

TEST_F(LabExportTest, AMetadataBlockAndAUnitsRowReadTheSameNumbers) {
  const Recording plain = Plain();
  Channels layout;
  layout.layout = R"({"lines_before_header": 5, "units_row": true})";
  // Separators and numbers in the metadata: nothing of it is a table.
  const std::string metadata = "Export,Acquisition 4.2\nSample rate,5120,Hz\nDate,2024-03-01\n\nChannels,3\n";
  ExpectSameRecording(Read(layout, Table({"Time", "drive", "acc1", "vel2"}, columns_, metadata, "s,V,g,mm/s\n")),
                      plain);
  // Bracketed and blank units, and a bracketed header unit the row repeats.
  ExpectSameRecording(
      Read(layout, Table({"Time", "drive", "acc1 [g]", "vel2"}, columns_, metadata, "[s],[V],g,\n")), plain);
  // A header with its units as suffixes keeps them; the units row agrees.
  ExpectSameRecording(
      Read(layout, Table({"time_s", "drive_V", "acc1", "vel2"}, columns_, metadata, "s,V,g,mm/s\n")), plain);
  ExpectNames(Error(layout, Table({"time_ms", "drive", "acc1", "vel2"}, columns_, metadata, "s,V,g,mm/s\n")),
              "time_ms", "the time column's header says 'ms' but the units row (line 7) gives 's'");
  Channels units_only;
  units_only.layout = R"({"units_row": true})";
  units_only.drive = Channel("drive", "voltage", "mV");
  ExpectSameRecording(
      Read(units_only, Table({"Time", "drive", "acc1", "vel2"}, Scaled(columns_, 1, 1e3), "", "s, mV, g, mm/s\n")),
      plain);
}

TEST_F(LabExportTest, AColumnMappingThatFindsNoColumnNamesTheChannelAndTheColumns) {
  const std::string text = Table({"Time [s]", "Ch1 Drive [V]", "Ch2 acc1 [g]", "vel2"}, columns_);
  Channels wrong_text;
  wrong_text.acc1 = Channel("acc1", "acceleration", "g", R"("column": "Ch2 acc [g]")");
  const InputError no_column = Error(wrong_text, text);
  ExpectNames(no_column, "acc1", R"(campaign.json's "column": "Ch2 acc [g]" names no column of the header (line 1))");
  EXPECT_NE(std::string(no_column.what()).find("'Ch2 acc1 [g]'"), std::string::npos) << no_column.what();

  Channels wrong_number;
  wrong_number.drive = Channel("drive", "voltage", "V", R"("column_number": 7)");
  ExpectNames(Error(wrong_number, text), "drive",
              R"(campaign.json's "column_number": 7 lies beyond the recording's columns: the header (line 1) has 4)");

  Channels twice;
  twice.drive = Channel("drive", "voltage", "V", R"("column": "x [V]")");
  ExpectNames(Error(twice, Table({"time_s", "x [V]", "acc1", "x [V]"}, columns_)), "drive",
              "names 2 columns of the header (line 1) (columns 2 and 4)");

  // A mapped column's unit is checked like a named one's.
  Channels wrong_unit;
  wrong_unit.drive = Channel("drive", "voltage", "V", R"("column": "Ch1 Drive [V]")");
  ExpectNames(Error(wrong_unit, Table({"Time [s]", "Ch1 Drive [V]", "acc1 [m/s^2]", "vel2"}, columns_)), "acc1",
              "the header gives the unit 'm/s^2' but campaign.json declares 'g'");
}

TEST_F(LabExportTest, ALayoutTheFileBreaksIsNamedWithTheFix) {
  Channels layout;
  layout.layout = R"({"lines_before_header": 5, "units_row": true})";
  const std::vector<std::string> header = {"Time", "drive", "acc1", "vel2"};
  ExpectNames(Error(layout, "Export,Acquisition 4.2\nDate,2024-03-01\n"), "",
              "the file has 2 lines, fewer than the 5 lines before the header that the layout skips");
  const std::string metadata = "a\nb\nc\nd\ne\n";
  ExpectNames(Error(layout, Table(header, columns_, metadata, "s,V,Pa,mm/s\n")), "acc1",
              "the units row (line 7) gives the unit 'Pa', which is not a unit of acceleration");
  ExpectNames(Error(layout, Table(header, columns_, metadata, "s,V,g\n")), "",
              "the units row (line 7, under the header) has 3 cells, the header 4");
  ExpectNames(Error(layout, Table(header, columns_, metadata)), "",
              "the units row (line 7, under the header) holds numbers");
  ExpectNames(Error(layout, Table({"Time", "drive", "acc1 [m/s^2]", "vel2"}, columns_, metadata, "s,V,g,mm/s\n")),
              "acc1 [m/s^2]",
              "the header gives the unit 'm/s^2' but the units row (line 7, under the header) gives 'g'");
  ExpectNames(Error(layout, metadata + "Time,drive,acc1,vel2\n"), "",
              "the units row (line 7, under the header) is missing: the file ends after the header");
  // A metadata block longer than declared: its last line is read as the header.
  layout.layout = R"({"lines_before_header": 4, "units_row": true})";
  const InputError short_block =
      Error(layout, Table(header, columns_, "a\nb\nc\nd\nOperator,J. Doe\n", "s,V,g,mm/s\n"));
  ExpectNames(short_block, "", "the units row (line 6, under the header) has 4 cells, the header 2");
  layout.layout = R"({"lines_before_header": 4})";
  ExpectNames(Error(layout, Table(header, columns_, "a\nb\nc\nd\nOperator;J. Doe\n")), "drive",
              "the header read is line 5");
}

TEST_F(LabExportTest, CampaignJsonRefusesAMappingOrLayoutThatCannotBeMeant) {
  const auto refused = [&](const Channels& channels) {
    std::ofstream(folder_ / "campaign.json") << CampaignJson(channels);
    std::ofstream(folder_ / "step.csv") << Table({"time_s", "drive", "acc1", "vel2"}, columns_);
    return InputErrorOf([&] { ReadCampaign(folder_); });
  };
  Channels both;
  both.acc1 = Channel("acc1", "acceleration", "g", R"("column": "Ch2 [g]", "column_number": 2)");
  std::string message = refused(both);
  EXPECT_NE(message.find(R"(sensors[0]: gives both "column": "Ch2 [g]" and "column_number": 2)"), std::string::npos)
      << message;
  EXPECT_NE(message.find("'acc1'"), std::string::npos) << message;

  Channels shared;
  shared.acc1 = Channel("acc1", "acceleration", "g", R"("column_number": 3)");
  shared.vel2 = Channel("vel2", "velocity", "mm/s", R"("column_number": 3)");
  message = refused(shared);
  EXPECT_NE(message.find(R"(sensors[1]: reads the same recording column as sensors[0] (acc1): "column_number": 3)"),
            std::string::npos)
      << message;

  Channels zero;
  zero.acc1 = Channel("acc1", "acceleration", "g", R"("column_number": 0)");
  message = refused(zero);
  EXPECT_NE(message.find("sensors[0].column_number\" = 0 lies outside 1 .. 10000"), std::string::npos) << message;

  Channels misspelt;
  misspelt.layout = R"({"header_lines": 3})";
  message = refused(misspelt);
  EXPECT_NE(message.find("recording_layout.header_lines\" is not a field here"), std::string::npos) << message;
  EXPECT_NE(message.find("lines_before_header, units_row"), std::string::npos) << message;
}

}  // namespace
}  // namespace beamid::signal
