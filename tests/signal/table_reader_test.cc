// The text tables of acquisition systems (signal/table_reader.h): a gallery of
// exports of one clean recording — separators, decimal comma, quoted and unit
// headers, extra channels, time in ms, time rounded to its printed digits, no
// time column, BOM/CRLF/comments — each read through ReadRecording (as
// ExtractCampaign does) gives the phasors of the clean CSV within 1e-9; the
// same for first-harmonic phasor tables; and the errors name the convention
// detected, the file, the channel and the fix.
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

#include "signal/campaign.h"
#include "signal/input_error.h"
#include "signal/phasor_estimator.h"
#include "signal/phasor_table.h"
#include "signal/recording.h"
#include "tests/signal/synthetic_signal.h"
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
  bool bom = false, crlf = false, comments = false, quoted = false, trailing_blanks = false;
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
  const std::string eol = e.crlf ? "\r\n" : "\n";
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
