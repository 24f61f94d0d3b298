// The text tables of acquisition systems (signal/table_reader.h): a gallery of
// exports of one clean recording — separators, decimal comma, quoted and unit
// headers, extra channels, time in ms, time rounded to its printed digits, no
// time column, BOM/CRLF/comments — each read through ReadRecording (as
// ExtractCampaign does) gives the phasors of the clean CSV within 1e-9; the
// same for first-harmonic phasor tables; and the errors name the convention
// detected, the file, the channel and the fix, quoting at most a short
// printable excerpt of the file. What is no table (a file of NUL bytes, a
// line of megabytes) is refused at once, in memory of the file's size, and
// a file of blank lines reserves nothing.
#include "signal/table_reader.h"

#include <cmath>
#include <complex>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "signal/campaign.h"
#include "signal/input_error.h"
#include "signal/phasor_estimator.h"
#include "signal/phasor_table.h"
#include "signal/internal/text.h"
#include "signal/recording.h"
#include "tests/signal/synthetic_signal.h"
#include "tests/support/memory_in_child.h"
#include "tests/support/temp_path.h"

namespace beamid::signal {
namespace {

namespace fs = std::filesystem;

constexpr double kRateHz = 5120.0;
constexpr int kSamples = 5120;
constexpr double kFrequencyHz = 40.013;
constexpr double kGravity = 9.80665;

std::string CampaignJson(bool with_sample_rate) {
  return std::string(R"({
  "format": "stepped-sine-campaign/1", "name": "gallery",
  "beam": {"length_m": 0.6, "width_m": 0.04, "thickness_m": 0.005, "youngs_modulus_Pa": 2.1e11, "density_kg_m3": 7850},
  "excitation": {"channel": "force", "position_m": 0.57, "quantity": "force", "unit": "N"},
  "sensors": [{"channel": "acc1", "position_m": 0.1, "quantity": "acceleration", "unit": "g"},
              {"channel": "vel2", "position_m": 0.3, "quantity": "velocity", "unit": "mm/s"}],
  "steps": [{"file": "step.csv", "frequency_Hz": 40.0, "level": "low"}])") +
         (with_sample_rate ? R"(, "sample_rate_Hz": 5120})" : "}");
}

// How an export is written.
struct Export {
  char separator = ',';
  bool decimal_comma = false;
  std::vector<std::string> headers = {"time_s", "force", "acc1", "vel2"};  // time first, then the channels
  enum class Time { kSeconds, kMilliseconds, kRounded4, kNone } time = Time::kSeconds;
  bool extra_columns = false;  // a temperature and an unlisted accelerometer
  bool bom = false, crlf = false, cr = false, comments = false, quoted = false, trailing_blanks = false;
  bool reversed = false;       // channels in another order than campaign.json
};

// The clean record in file units (N, g, mm/s): columns force, acc1, vel2.
Eigen::MatrixXd CleanRecord() {
  std::mt19937 rng(11);
  std::normal_distribution<double> normal;
  Eigen::MatrixXd x(kSamples, 3);
  for (int c = 0; c < 3; ++c) {
    testing::Tone tone = testing::RandomTone(rng, 5, kFrequencyHz, 1.0 + c);
    tone.sample_rate_hz = kRateHz;
    x.col(c) = testing::Synthesize(tone, kSamples, 0.0);
    for (int n = 0; n < kSamples; ++n) x(n, c) += 1e-3 * (1.0 + c) * normal(rng);
  }
  x.col(1) /= kGravity;
  x.col(2) *= 1e3;
  return x;
}

std::string Render(const Eigen::MatrixXd& x, const Export& e) {
  const std::string eol = e.cr ? "\r" : e.crlf ? "\r\n" : "\n";
  const std::string sep(1, e.separator);
  auto number = [&](const char* format, double value) {
    char buffer[64];
    std::snprintf(buffer, sizeof buffer, format, value);
    std::string s = buffer;
    if (e.decimal_comma)
      for (char& c : s)
        if (c == '.') c = ',';
    return s;
  };
  auto quote = [&](const std::string& h) { return e.quoted ? "\"" + h + "\"" : h; };
  std::vector<int> order = {0, 1, 2};
  if (e.reversed) order = {2, 0, 1};
  std::string text = e.bom ? "\xEF\xBB\xBF" : "";
  if (e.comments) text += "# exported by a gallery" + eol + "% sample rate 5120 Hz" + eol + "// operator: test" + eol;
  std::vector<std::string> header;
  if (e.time != Export::Time::kNone) header.push_back(quote(e.headers[0]));
  for (int c : order) header.push_back(quote(e.headers[static_cast<std::size_t>(c + 1)]));
  if (e.extra_columns) {
    header.insert(header.begin() + 1, quote("temperature [degC]"));
    header.push_back(quote("acc9 [m/s^2]"));
  }
  for (std::size_t i = 0; i < header.size(); ++i) text += (i ? sep : "") + header[i];
  text += eol;
  for (int n = 0; n < kSamples; ++n) {
    std::vector<std::string> cells;
    const double t = n / kRateHz;
    switch (e.time) {
      case Export::Time::kSeconds: cells.push_back(number("%.10f", t)); break;
      case Export::Time::kMilliseconds: cells.push_back(number("%.7f", 1e3 * t)); break;
      case Export::Time::kRounded4: cells.push_back(number("%.4f", t)); break;
      case Export::Time::kNone: break;
    }
    for (int c : order) cells.push_back(number("%.9g", x(n, c)));
    if (e.extra_columns) {
      cells.insert(cells.begin() + 1, number("%.2f", 21.5 + 0.01 * (n % 7)));
      cells.push_back(number("%.6f", std::sin(0.3 * n)));
    }
    for (std::size_t i = 0; i < cells.size(); ++i) text += (i ? sep : "") + cells[i];
    text += eol;
    if (e.comments && n == kSamples / 2) text += "# half way" + eol;
  }
  if (e.trailing_blanks) text += eol + eol + "  " + eol;
  return text;
}

class TableReaderGallery : public ::testing::Test {
 protected:
  void SetUp() override {
    folder_ = beamid::testing::UniqueTempPath("beamid_table_reader");
    fs::remove_all(folder_);
    fs::create_directories(folder_);
  }
  void TearDown() override { fs::remove_all(folder_); }

  // Writes the export and campaign.json, reads them as ExtractCampaign does.
  Recording Read(const std::string& text, bool with_sample_rate) {
    std::ofstream(folder_ / "campaign.json") << CampaignJson(with_sample_rate);
    std::ofstream(folder_ / "step.csv", std::ios::binary) << text;
    campaign_ = ReadCampaign(folder_);
    return ReadRecording(campaign_, campaign_.steps.front());
  }
  StepPhasors Phasors(const std::string& text, bool with_sample_rate) {
    const Recording recording = Read(text, with_sample_rate);
    return EstimateStepPhasors(recording, campaign_, campaign_.steps.front());
  }
  InputError Error(const std::string& text, bool with_sample_rate) {
    try {
      Read(text, with_sample_rate);
    } catch (const InputError& e) {
      return e;
    }
    ADD_FAILURE() << "no InputError";
    return InputError("", "", "", "");
  }
  std::string StepFile() const { return (folder_ / "step.csv").string(); }

  fs::path folder_;
  Campaign campaign_;
};

double MaxDifference(const StepPhasors& a, const StepPhasors& b) {
  double worst = std::abs(a.frequency_hz - b.frequency_hz);
  for (const char* name : {"force", "acc1", "vel2"})
    for (int k = 1; k <= 5; ++k)
      worst = std::max(worst, std::abs(a.Find(name)->Harmonic(k).value - b.Find(name)->Harmonic(k).value));
  return worst;
}

TEST_F(TableReaderGallery, EveryExportGivesThePhasorsOfTheCleanCsv) {
  const Eigen::MatrixXd x = CleanRecord();
  const StepPhasors clean = Phasors(Render(x, {}), /*with_sample_rate=*/false);
  const StepPhasors clean_with_rate = Phasors(Render(x, {}), /*with_sample_rate=*/true);
  EXPECT_EQ(MaxDifference(clean, clean_with_rate), 0.0);

  struct Variant {
    std::string name;
    Export e;
    bool with_sample_rate = false;
  };
  std::vector<Variant> gallery;
  auto add = [&](const std::string& name, const std::function<void(Export&)>& edit, bool rate = false) {
    Export e;
    edit(e);
    gallery.push_back({name, e, rate});
  };
  add("semicolon", [](Export& e) { e.separator = ';'; });
  add("tab", [](Export& e) { e.separator = '\t'; });
  add("semicolon, decimal comma", [](Export& e) { e.separator = ';', e.decimal_comma = true; });
  add("tab, decimal comma", [](Export& e) { e.separator = '\t', e.decimal_comma = true; });
  add("quoted headers", [](Export& e) { e.quoted = true; });
  add("units in brackets", [](Export& e) { e.headers = {"time [s]", "force [N]", "acc1 [g]", "vel2 [mm/s]"}; });
  add("units in parentheses, quoted",
      [](Export& e) { e.headers = {"Time (s)", "force (N)", "acc1 (G)", "vel2 (mm/s)"}, e.quoted = true; });
  add("unit suffixes", [](Export& e) { e.headers = {"t_s", "force_N", "acc1_g", "vel2_mm_s"}; });
  add("extra channels, other order", [](Export& e) { e.extra_columns = true, e.reversed = true; });
  add("time in ms", [](Export& e) { e.time = Export::Time::kMilliseconds, e.headers[0] = "time [ms]"; });
  add("time in ms, suffix", [](Export& e) { e.time = Export::Time::kMilliseconds, e.headers[0] = "t_ms"; });
  add("time rounded to 4 decimals", [](Export& e) { e.time = Export::Time::kRounded4; }, true);
  add("no time column", [](Export& e) { e.time = Export::Time::kNone; }, true);
  add("BOM, CRLF, comments, trailing blank lines",
      [](Export& e) { e.bom = true, e.crlf = true, e.comments = true, e.trailing_blanks = true; });
  add("CR line ends (CSV Macintosh), comments, trailing blank lines",
      [](Export& e) { e.cr = true, e.comments = true, e.trailing_blanks = true; });
  add("everything at once", [](Export& e) {
    e.separator = ';', e.decimal_comma = true, e.quoted = true, e.extra_columns = true, e.reversed = true;
    e.headers = {"time [ms]", "force [N]", "acc1 (g)", "vel2_mm_s"}, e.time = Export::Time::kMilliseconds;
    e.bom = true, e.crlf = true, e.comments = true, e.trailing_blanks = true;
  });
  for (const Variant& v : gallery) {
    SCOPED_TRACE(v.name);
    const std::string text = Render(x, v.e);
    const Recording recording = Read(text, v.with_sample_rate);
    EXPECT_EQ(recording.channels, (std::vector<std::string>{"force", "acc1", "vel2"}));
    EXPECT_EQ(recording.NumSamples(), kSamples);
    EXPECT_NEAR(recording.sample_rate_hz, kRateHz, 1e-9);
    if (v.e.extra_columns)
      EXPECT_EQ(recording.ignored_columns, (std::vector<std::string>{"temperature [degC]", "acc9 [m/s^2]"}));
    else
      EXPECT_TRUE(recording.ignored_columns.empty());
    const double difference = MaxDifference(Phasors(text, v.with_sample_rate), clean);
    std::cout << "  " << v.name << ": max |phasor difference| vs clean = " << difference << "\n";
    EXPECT_LE(difference, 1e-9);
  }
}

// Without sample_rate_Hz, rounded times give the rate of their least-squares
// line: as exact as the printed digits allow.
TEST_F(TableReaderGallery, RoundedTimeWithoutSampleRateUsesTheLeastSquaresRate) {
  const Eigen::MatrixXd x = CleanRecord();
  const StepPhasors clean = Phasors(Render(x, {}), false);
  Export e;
  e.time = Export::Time::kRounded4;
  const Recording recording = Read(Render(x, e), false);
  std::cout << "  rounded time, no sample_rate_Hz: rate " << recording.sample_rate_hz - kRateHz << " Hz off\n";
  EXPECT_NEAR(recording.sample_rate_hz, kRateHz, 1e-2);
  const StepPhasors rounded = Phasors(Render(x, e), false);
  const double difference = MaxDifference(rounded, clean);
  std::cout << "  rounded time, no sample_rate_Hz: max |phasor difference| vs clean = " << difference << "\n";
  EXPECT_LE(difference, 1e-4);
}

TEST_F(TableReaderGallery, AHeaderUnitThatContradictsCampaignJsonNamesBoth) {
  Export e;
  e.headers = {"time_s", "force", "acc1 [m/s^2]", "vel2"};
  const InputError error = Error(Render(CleanRecord(), e), false);
  const std::string message = error.what();
  EXPECT_EQ(error.file(), StepFile());
  EXPECT_EQ(error.channel(), "acc1");
  EXPECT_NE(message.find("the header gives the unit 'm/s^2' but campaign.json declares 'g'"), std::string::npos)
      << message;
  EXPECT_NE(message.find("Fix: "), std::string::npos) << message;
  e.headers = {"time_s", "force", "acc1 [mm]", "vel2"};
  EXPECT_NE(std::string(Error(Render(CleanRecord(), e), false).what()).find("'mm', which is not a unit of acceleration"),
            std::string::npos);
}

TEST_F(TableReaderGallery, NoTimeColumnAndNoSampleRateSaysToAddOne) {
  Export e;
  e.time = Export::Time::kNone;
  const InputError error = Error(Render(CleanRecord(), e), false);
  const std::string message = error.what();
  EXPECT_EQ(error.file(), StepFile());
  EXPECT_NE(message.find("no time column and campaign.json gives no sample_rate_Hz"), std::string::npos) << message;
  EXPECT_NE(message.find("Fix: add a time column (time_s, or time [ms]) to the recording, or \"sample_rate_Hz\""),
            std::string::npos)
      << message;
}

TEST_F(TableReaderGallery, ANonNumberUnderDecimalCommaNamesTheConvention) {
  Export e;
  e.separator = ';';
  e.decimal_comma = true;
  std::string text = Render(CleanRecord(), e);
  // Line 12 (header on line 1): acc1, the third cell.
  std::size_t start = 0;
  for (int i = 0; i < 11; ++i) start = text.find('\n', start) + 1;
  const std::size_t a = text.find(';', text.find(';', start) + 1) + 1;
  text.replace(a, text.find(';', a) - a, "abc");
  const InputError error = Error(text, false);
  const std::string message = error.what();
  EXPECT_EQ(error.channel(), "acc1");
  EXPECT_NE(message.find("the file uses ';' as separator and ',' as decimal mark: line 12, column acc1: 'abc' is not "
                         "a number"),
            std::string::npos)
      << message;
  // A decimal point among decimal commas is no number either.
  text.replace(a, 3, "0.5");
  EXPECT_NE(std::string(Error(text, false).what()).find("'0.5' is not a number"), std::string::npos);
}

TEST_F(TableReaderGallery, RoundedTimeStillShowsAMissingSampleAndTooCoarseTimeIsRefused) {
  Export e;
  e.time = Export::Time::kRounded4;
  std::string text = Render(CleanRecord(), e);
  std::size_t row = 0;
  for (int i = 0; i < 2001; ++i) row = text.find('\n', row) + 1;
  text.erase(row, text.find('\n', row) + 1 - row);
  const std::string missing = Error(text, true).what();
  EXPECT_NE(missing.find("non-uniform sampling at line 2002"), std::string::npos) << missing;
  EXPECT_NE(missing.find("rounding of its printed digits"), std::string::npos) << missing;

  std::string coarse = "time_s,force,acc1,vel2\n";
  const Eigen::MatrixXd x = CleanRecord();
  char line[160];
  for (int n = 0; n < kSamples; ++n) {
    std::snprintf(line, sizeof line, "%.3f,%.9g,%.9g,%.9g\n", n / kRateHz, x(n, 0), x(n, 1), x(n, 2));
    coarse += line;
  }
  const std::string refused = Error(coarse, true).what();
  EXPECT_NE(refused.find("printed with too few digits to show a missing sample"), std::string::npos) << refused;
  EXPECT_NE(refused.find("give sample_rate_Hz"), std::string::npos) << refused;
}

TEST_F(TableReaderGallery, ATimeColumnWithoutUnitOrTwoTimeColumnsAreRefused) {
  Export e;
  e.headers = {"time", "force", "acc1", "vel2"};
  EXPECT_NE(std::string(Error(Render(CleanRecord(), e), false).what()).find("the time column has no unit"),
            std::string::npos);
  e.headers = {"time_s", "force", "acc1", "vel2"};
  e.extra_columns = true;
  std::string text = Render(CleanRecord(), e);
  text.replace(text.find("temperature [degC]"), 18, "t_ms");
  EXPECT_NE(std::string(Error(text, false).what()).find("two time columns ('time_s' and 't_ms')"), std::string::npos);
}

TEST_F(TableReaderGallery, ASpaceSeparatedHeaderIsNamedAsOneColumn) {
  Export e;
  std::string text = Render(CleanRecord(), e);
  text.replace(0, text.find('\n'), "time_s force acc1 vel2");
  const InputError error = Error(text, false);
  EXPECT_EQ(error.channel(), "force");
  EXPECT_NE(std::string(error.what()).find("'time_s force acc1 vel2'; the header is a single column, so the file uses "
                                           "',' as separator"),
            std::string::npos)
      << error.what();
}

// A file of zeros (an unfinished copy, a damaged disk) is refused at its
// first byte: nothing of it is split into cells, copied into a header or
// quoted, so the memory is the file's text alone.
TEST_F(TableReaderGallery, ABigFileOfNulBytesIsRefusedAtOnceInMemoryOfItsSize) {
  constexpr long long kBytes = 50LL << 20;
  std::ofstream(folder_ / "campaign.json") << CampaignJson(false);
  {
    std::ofstream csv(folder_ / "step.csv", std::ios::binary);
    const std::string zeros(1 << 20, '\0');
    for (long long written = 0; written < kBytes; written += static_cast<long long>(zeros.size())) csv << zeros;
  }
  campaign_ = ReadCampaign(folder_);
  const auto run = beamid::testing::MemoryInChild(3 * kBytes, [&] {
    try {
      ReadRecording(campaign_, campaign_.steps.front());
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  });
  ASSERT_TRUE(run.ran);
  std::cout << "  50 MB of NUL bytes: refused with " << run.text.size() << " characters, peak resident growth "
            << run.growth_bytes / (1 << 20) << " MB\n";
  EXPECT_NE(run.text.find(StepFile()), std::string::npos) << run.text;
  EXPECT_NE(run.text.find("byte 1 (line 1) is a NUL: the file is binary or UTF-16, not a text table"),
            std::string::npos)
      << run.text;
  EXPECT_NE(run.text.find("Fix: "), std::string::npos) << run.text;
  EXPECT_LT(run.text.size(), 500u);
  EXPECT_LT(run.growth_bytes, 3 * kBytes);
}

// 50 MB of blank lines after a record are trailing blank lines: harmless,
// and they reserve nothing (rows are counted before the samples are).
TEST_F(TableReaderGallery, TrailingBlankLinesReserveNothing) {
  constexpr long long kBytes = 50LL << 20;
  std::ofstream(folder_ / "campaign.json") << CampaignJson(false);
  {
    std::ofstream csv(folder_ / "step.csv", std::ios::binary);
    csv << Render(CleanRecord(), {});
    const std::string newlines(1 << 20, '\n');
    for (long long written = 0; written < kBytes; written += static_cast<long long>(newlines.size())) csv << newlines;
  }
  campaign_ = ReadCampaign(folder_);
  const auto run = beamid::testing::MemoryInChild(3 * kBytes, [&] {
    try {
      return "samples " + std::to_string(ReadRecording(campaign_, campaign_.steps.front()).NumSamples());
    } catch (const InputError& e) {
      return std::string(e.what());
    }
  });
  ASSERT_TRUE(run.ran);
  std::cout << "  a record and 50 MB of blank lines: peak resident growth " << run.growth_bytes / (1 << 20) << " MB\n";
  EXPECT_EQ(run.text, "samples " + std::to_string(kSamples));
  EXPECT_LT(run.growth_bytes, 3 * kBytes);
}

TEST_F(TableReaderGallery, AFileWithoutTwoRowsIsRefusedBeforeAnythingIsReserved) {
  std::string text = "time_s,force,acc1,vel2\n";
  for (int i = 0; i < 100000; ++i) text += "# a comment, no sample\n\n";
  const std::string message = Error(text + "0,1,2,3\n", false).what();
  EXPECT_NE(message.find("fewer than two samples (1 data row after the header on line 1)"), std::string::npos)
      << message;
}

TEST_F(TableReaderGallery, ANumberBeyondADoubleIsOutOfRangeNotNoNumber) {
  Export e;
  for (const char* value : {"1e400", "-1e400", "1e-400"}) {
    std::string text = Render(CleanRecord(), e);
    const std::size_t line5 = [&] {
      std::size_t at = 0;
      for (int i = 0; i < 4; ++i) at = text.find('\n', at) + 1;
      return at;
    }();
    const std::size_t a = text.find(',', text.find(',', line5) + 1) + 1;  // acc1, the third cell
    text.replace(a, text.find(',', a) - a, value);
    const InputError error = Error(text, false);
    EXPECT_EQ(error.channel(), "acc1");
    EXPECT_NE(std::string(error.what()).find("line 5, column acc1: '" + std::string(value) + "' is out of range"),
              std::string::npos)
        << error.what();
  }
}

// Whatever a file holds, a message quotes a short printable excerpt of it,
// in valid UTF-8 (a message reaches the phasors file as a skipped step's
// reason, and the JSON writer throws on invalid UTF-8).
TEST_F(TableReaderGallery, MessagesQuoteAShortPrintableExcerptOfTheFile) {
  const Eigen::MatrixXd x = CleanRecord();
  std::string text = Render(x, {});
  const std::size_t line3 = text.find('\n', text.find('\n') + 1) + 1;
  const std::size_t a = text.find(',', text.find(',', line3) + 1) + 1;
  text.replace(a, text.find(',', a) - a, "\x01\xE9\x7F" + std::string(100000, 'x'));
  std::vector<std::pair<std::string, std::string>> cases = {
      {"a cell of control, Latin-1 and 100000 more bytes", text}};
  // Thousands of unused columns and a missing channel: the list stays short.
  std::string wide = "time_s,force,vel2";
  for (int i = 0; i < 5000; ++i) wide += ",spare" + std::to_string(i);
  cases.emplace_back("5000 unused columns", wide + "\n");
  cases.emplace_back("one line of 2 MB", "time_s" + std::string(2 << 20, ' ') + "x");
  std::string many = "a";
  for (int i = 0; i < 20000; ++i) many += ",a";
  cases.emplace_back("a header of 20001 columns", many + "\n");
  const std::vector<std::string> expected = {
      // 40 characters: three escaped bytes and 37 of the x.
      "line 3, column acc1: '\\x01\\xE9\\x7F" + std::string(37, 'x') + "\xE2\x80\xA6 (100003 bytes)' is not a number",
      "channel 'acc1': the channel of campaign.json is missing from the header (columns no channel uses: 'spare0', "
      "'spare1', 'spare2', 'spare3', 'spare4', 'spare5', 'spare6', 'spare7' and 4992 more)",
      "the header (line 1) is 2097159 bytes long, beyond any table's header; it begins 'time_s",
      "the header (line 1) has 20001 columns, more than the 10000 a table may have"};
  for (std::size_t i = 0; i < cases.size(); ++i) {
    SCOPED_TRACE(cases[i].first);
    const std::string message = Error(cases[i].second, false).what();
    EXPECT_NE(message.find(expected[i]), std::string::npos) << message.substr(0, 2000);
    EXPECT_NE(message.find(StepFile()), std::string::npos);
    EXPECT_LT(message.size(), 1000u);
    EXPECT_TRUE(internal::IsValidUtf8(message));
    EXPECT_NO_THROW(static_cast<void>(nlohmann::json(message).dump()));
  }
}

// A Latin-1 header of a column no channel uses is a note, its name kept
// with the bytes escaped; a channel's unit that is not UTF-8 is refused,
// naming the file and the channel.
TEST_F(TableReaderGallery, HeadersThatAreNotUtf8AreANoteOrAnErrorByTheirUse) {
  Export e;
  e.extra_columns = true;
  std::string text = Render(CleanRecord(), e);
  text.replace(text.find("temperature [degC]"), 18, "temperature [\xB0" "C]");
  const Recording recording = Read(text, false);
  EXPECT_EQ(recording.ignored_columns, (std::vector<std::string>{"temperature [\\xB0C]", "acc9 [m/s^2]"}));
  ASSERT_EQ(recording.findings.size(), 1u);
  EXPECT_EQ(recording.findings[0].severity, Severity::kNote);
  EXPECT_NE(recording.findings[0].problem.find("column 2's header 'temperature [\\xB0C]' is not UTF-8 text"),
            std::string::npos)
      << recording.findings[0].problem;

  e.extra_columns = false;
  e.headers = {"time_s", "force", "acc1 [m/s\xB2]", "vel2"};
  const InputError error = Error(Render(CleanRecord(), e), false);
  EXPECT_EQ(error.file(), StepFile());
  EXPECT_EQ(error.channel(), "acc1");
  EXPECT_NE(std::string(error.what()).find("the header gives the unit 'm/s\\xB2', which is not UTF-8 text"),
            std::string::npos)
      << error.what();
  EXPECT_TRUE(internal::IsValidUtf8(error.what()));
}

// Sensors acc1 and acc1_g: a header cell is the channel it names whole, so
// acc1_g is never taken for acc1 in g, in any column order.
TEST(ChannelMatching, ChannelNamesMatchWholeHeaderFieldsNotPrefixes) {
  const std::string json = R"({
  "format": "stepped-sine-campaign/1", "name": "prefixes",
  "beam": {"length_m": 0.6, "width_m": 0.04, "thickness_m": 0.005, "youngs_modulus_Pa": 2.1e11, "density_kg_m3": 7850},
  "excitation": {"channel": "force", "position_m": 0.57, "quantity": "force", "unit": "N"},
  "sensors": [{"channel": "acc1", "position_m": 0.1, "quantity": "acceleration", "unit": "m/s^2"},
              {"channel": "acc1_g", "position_m": 0.3, "quantity": "acceleration", "unit": "g"}],
  "steps": [{"file": "step.csv", "frequency_Hz": 40.0, "level": "low"}], "sample_rate_Hz": 5120})";
  const Campaign campaign = ParseCampaign(json, "prefixes", "prefixes/campaign.json");
  constexpr int kRows = 2048;
  auto value = [](int channel, int n) {
    const double phase = 2.0 * std::numbers::pi * kFrequencyHz * n / kRateHz;
    return channel == 0 ? std::sin(phase) : channel == 1 ? 2.0 * std::cos(phase) : 0.25 * std::sin(phase + 1.0);
  };
  for (const std::vector<std::string>& header :
       {std::vector<std::string>{"force", "acc1", "acc1_g"}, {"force", "acc1_g", "acc1"},
        {"acc1_g [g]", "force", "acc1 [m/s^2]"}, {"acc1_g_g", "acc1", "force"}}) {
    SCOPED_TRACE(header[0] + "," + header[1] + "," + header[2]);
    std::vector<int> channel_of;  // campaign channel of each column
    for (const auto& cell : header)
      channel_of.push_back(cell.starts_with("force") ? 0 : cell.starts_with("acc1_g") ? 2 : 1);
    std::string text = header[0] + "," + header[1] + "," + header[2] + "\n";
    char line[120];
    for (int n = 0; n < kRows; ++n) {
      std::snprintf(line, sizeof line, "%.12g,%.12g,%.12g\n", value(channel_of[0], n), value(channel_of[1], n),
                    value(channel_of[2], n));
      text += line;
    }
    const Recording recording = ParseRecording(text, campaign, campaign.steps.front(), "prefixes/step.csv");
    ASSERT_EQ(recording.channels, (std::vector<std::string>{"force", "acc1", "acc1_g"}));
    for (int n = 0; n < kRows; n += 97) {
      EXPECT_NEAR(recording.samples(n, 1), value(1, n), 1e-11);
      EXPECT_NEAR(recording.samples(n, 2), kGravity * value(2, n), 1e-11);
    }
  }
}

TEST(TableReader, RefusesWhatIsNoTextTable) {
  for (const auto& [text, expected] : std::vector<std::pair<std::string, std::string>>{
           {std::string("\xFF\xFEt\0i\0m\0e\0", 10), "the file is UTF-16 text"},
           {std::string("time_s,force\n0,1\n0.1,\0\n", 23), "byte 22 (line 3) is a NUL"}}) {
    try {
      TableReader table(text, "x.csv", {});
      ADD_FAILURE() << "accepted";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(expected), std::string::npos) << e.what();
      EXPECT_EQ(e.file(), "x.csv");
    }
  }
  TableReader cr("a,b\r1,2\r\r3,4\r", "cr.csv", {});
  EXPECT_EQ(cr.CountRows(), 2u);
  ASSERT_TRUE(cr.NextRow());
  EXPECT_EQ(cr.Line(), 2);
  EXPECT_EQ(cr.CellText(1), "2");
  EXPECT_THROW(cr.NextRow(), InputError);  // the blank line 3 inside the table
}

TEST(Excerpt, IsShortPrintableUtf8) {
  using internal::Excerpt;
  EXPECT_EQ(Excerpt("acc1 [m/s\xC2\xB2]"), "acc1 [m/s\xC2\xB2]");
  EXPECT_EQ(Excerpt(std::string("a\0b\tc\xB0\xC2\x85", 8)), "a\\x00b\\tc\\xB0\\xC2\\x85");
  EXPECT_EQ(Excerpt("\xED\xA0\x80"), "\\xED\\xA0\\x80");  // a surrogate
  EXPECT_EQ(Excerpt("\xF0\x9F\x98\x80"), "\xF0\x9F\x98\x80");
  EXPECT_EQ(Excerpt(std::string(50, 'y'), 4), "yyyy\xE2\x80\xA6 (50 bytes)");
  EXPECT_TRUE(internal::IsValidUtf8("m/s\xC2\xB2"));
  EXPECT_FALSE(internal::IsValidUtf8("m/s\xB2"));
  EXPECT_FALSE(internal::IsValidUtf8("\xC0\xAF"));  // overlong '/'
  EXPECT_FALSE(internal::IsValidUtf8("\xE2\x82"));  // cut short
}

TEST(TableReader, DetectsTheConventions) {
  TableReader semicolon("\xEF\xBB\xBF# comment\r\n\"a [N]\";b_g\r\n% note\r\n1,5;2\r\n", "x.csv", {});
  ASSERT_TRUE(semicolon.HasHeader());
  EXPECT_EQ(semicolon.HeaderLine(), 2);
  EXPECT_EQ(semicolon.Format().Describe(), "the file uses ';' as separator and ',' as decimal mark");
  ASSERT_EQ(semicolon.Header().size(), 2u);
  EXPECT_EQ(semicolon.Header()[0].name, "a");
  EXPECT_EQ(semicolon.Header()[0].unit, "N");
  EXPECT_EQ(SplitUnitSuffix(semicolon.Header()[1].text, "b"), "g");
  ASSERT_TRUE(semicolon.NextRow());
  EXPECT_EQ(semicolon.Line(), 4);
  double value = 0.0;
  PrintedPrecision precision;
  ASSERT_TRUE(semicolon.Number(0, value, &precision));
  EXPECT_EQ(value, 1.5);
  EXPECT_EQ(precision.decimals, 1);
  EXPECT_FALSE(semicolon.NextRow());

  TableReader tab("a\tb\n1.25e-3\t+2\n\n\n", "y.txt", {});
  EXPECT_EQ(tab.Format().Describe(), "the file uses tab as separator and '.' as decimal mark");
  ASSERT_TRUE(tab.NextRow());
  ASSERT_TRUE(tab.Number(0, value, &precision));
  EXPECT_EQ(precision.decimals, 5);
  EXPECT_EQ(precision.significant, 3);
  ASSERT_TRUE(tab.Number(1, value));
  EXPECT_EQ(value, 2.0);
  EXPECT_FALSE(tab.NextRow());

  EXPECT_EQ(NormaliseUnit("m/s²"), "m/s^2");
  EXPECT_EQ(NormaliseUnit("MM/S"), "mm/s");
  EXPECT_FALSE(NormaliseUnit("furlong").has_value());
}

// The phasor table reader goes through the same reader: the same level in
// acquisition-style exports reads the same phasors.
TEST(PhasorTableGallery, ExportsReadTheSamePhasors) {
  struct Row {
    double f, force, acc, phase;
  };
  const std::vector<Row> rows = {{53.5, 1.0, 2.25, 0.5}, {54.0, 1.1, 4.125, 1.5}, {54.5, 0.9, 2.5, 2.5}};
  auto render = [&](const std::string& header, char sep, bool comma, double acc_scale, double phase_scale,
                    const std::string& eol, const std::string& preamble, bool extra) {
    std::string text = preamble + header + eol;
    for (const Row& r : rows) {
      char line[200];
      const char s = sep;
      std::snprintf(line, sizeof line, "%.17g%c%.17g%c%.17g%c%.17g", r.f, s, r.force, s, r.acc / acc_scale, s,
                    r.phase / phase_scale);
      std::string l = line;
      if (extra) l += std::string(1, sep) + "0.99";
      if (comma)
        for (char& c : l)
          if (c == '.') c = ',';
      text += l + eol;
    }
    return text;
  };
  const FirstHarmonicLevel clean = ParsePhasorTable(
      render("frequency_Hz,force_N,acceleration_m_s2,phase_rad", ',', false, 1, 1, "\n", "", false), "clean.csv", "a");
  const double deg = std::numbers::pi / 180;
  const std::vector<std::pair<std::string, std::string>> gallery = {
      {"semicolon, decimal comma",
       render("frequency_Hz;force_N;acceleration_m_s2;phase_rad", ';', true, 1, 1, "\n", "", false)},
      {"tab, decimal comma, degrees",
       render("Frequency [Hz]\tForce [N]\tAcceleration [m/s²]\tPhase [deg]", '\t', true, 1, deg, "\n", "", false)},
      {"quoted, units in g and deg, coherence",
       render("\"Frequency (Hz)\",\"F_amp (N)\",\"Response (g)\",\"Phase (deg)\",\"Coherence\"", ',', false, kGravity,
              deg, "\n", "", true)},
      {"BOM, CRLF, comments",
       render("freq_Hz;force_N;acc_m_s2;phase_rad", ';', true, 1, 1, "\r\n",
              "\xEF\xBB\xBF% exported\r\n// by a system\r\n# with comments\r\n", false)},
  };
  for (const auto& [name, text] : gallery) {
    SCOPED_TRACE(name);
    const FirstHarmonicLevel level = ParsePhasorTable(text, "gallery.csv", "a");
    ASSERT_EQ(level.points.size(), clean.points.size());
    EXPECT_EQ(level.response_quantity, Quantity::kAcceleration);
    double worst = 0.0;
    for (std::size_t i = 0; i < clean.points.size(); ++i) {
      worst = std::max(worst, std::abs(level.points[i].frequency_hz - clean.points[i].frequency_hz));
      worst = std::max(worst, std::abs(level.points[i].force.value - clean.points[i].force.value));
      worst = std::max(worst, std::abs(level.points[i].response.value - clean.points[i].response.value));
    }
    std::cout << "  phasor table, " << name << ": max difference vs clean = " << worst << "\n";
    EXPECT_LE(worst, 1e-9);
  }
  try {
    ParsePhasorTable("f [Hz];force [N];acc [g];phase [deg]\n50;1;1,5;0\n51;1;abc;10\n52;1;1;20\n", "levels/high.csv",
                     "high");
    ADD_FAILURE() << "no error";
  } catch (const InputError& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find("levels/high.csv"), std::string::npos) << message;
    EXPECT_NE(message.find("the file uses ';' as separator and ',' as decimal mark: line 3, column 'acc [g]': 'abc' "
                           "is not a number"),
              std::string::npos)
        << message;
  }
}

}  // namespace
}  // namespace beamid::signal
