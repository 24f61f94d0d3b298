// What a person reads of a measured backbone (solver/report/measured_backbone_summary.h
// and the page of solver/report/measured_backbone_report.h) when estimators
// fail: tables of a clean level beside one of 3 steps, a flat one (the same
// |X/F| and phase at every step) and one with no peak (all below the mode),
// run through `backbone --measured`'s workflow and its file: the summary has
// exactly one line per level, neither the summary, the warnings nor the page
// holds "nan" or "inf", and each number not estimated says so and why. A
// level's flags read as short words, each kind once with its count.
#include "solver/report/measured_backbone_summary.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <regex>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "solver/backbone/measured_backbone_io.h"
#include "solver/report/measured_backbone_report.h"
#include "solver/workflow/measure_backbone.h"
#include "tests/support/temp_path.h"

namespace beamid::solver {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;

// One mode (1 kg, 50 Hz, ζ 1 %) under 1 N: X/F at f.
std::complex<double> Receptance(double f_hz) {
  const double wn = 2 * std::numbers::pi * 50.0, w = 2 * std::numbers::pi * f_hz;
  return 1.0 / std::complex<double>(wn * wn - w * w, 2 * 0.01 * wn * w);
}

// A phasor table (docs/phasor-table.md) of (frequency, X/F) rows under 1 N.
std::string Table(const std::filesystem::path& path, const std::vector<std::pair<double, std::complex<double>>>& rows) {
  std::ofstream out(path);
  out << "frequency_Hz,force_N,displacement_m,phase_rad\n";
  out.precision(12);
  for (const auto& [f, x] : rows) out << f << ",1," << std::abs(x) << ',' << std::arg(x) << '\n';
  return path.string();
}

std::vector<std::pair<double, std::complex<double>>> Sweep(double from_hz, double to_hz, int steps) {
  std::vector<std::pair<double, std::complex<double>>> rows;
  for (int i = 0; i < steps; ++i) {
    const double f = from_hz + (to_hz - from_hz) * i / (steps - 1);
    rows.push_back({f, Receptance(f)});
  }
  return rows;
}

// "nan", "inf" or "infinity" as a word, in any case.
bool HasUndefinedNumber(const std::string& text) {
  static const std::regex undefined("(^|[^a-z])(nan|inf|infinity)([^a-z]|$)", std::regex::icase);
  return std::regex_search(text, undefined);
}

std::string Joined(const std::vector<std::string>& lines) {
  std::string text;
  for (const auto& line : lines) text += line + "\n";
  return text;
}

TEST(MeasuredBackboneSummary, FailedEstimatorsAreSaidInWordsWithTheirReasonNeverAsNan) {
  const auto folder = beamid::testing::UniqueTempPath("measured_backbone_summary_test");
  std::filesystem::create_directories(folder);
  std::vector<std::pair<double, std::complex<double>>> flat;
  for (int i = 0; i < 20; ++i) flat.push_back({45.0 + 0.5 * i, {-1e-5, 1e-6}});
  const workflow::MeasureBackboneRequest request{
      .inputs = {Table(folder / "clean.csv", Sweep(45.0, 55.0, 101)),
                 Table(folder / "three.csv", Sweep(49.5, 50.5, 3)), Table(folder / "flat.csv", flat),
                 Table(folder / "nopeak.csv", Sweep(30.0, 40.0, 21))},
      .output = (folder / "out").string()};
  const workflow::MeasureBackboneOutcome outcome = workflow::MeasureBackbone(request);
  const MeasuredBackbone& measured = outcome.measured;
  ASSERT_EQ(measured.levels.size(), 4u);

  const std::vector<std::string> lines = LevelSummaryLines(measured);
  ASSERT_EQ(lines.size(), measured.levels.size());
  for (std::size_t l = 0; l < lines.size(); ++l) {
    EXPECT_EQ(lines[l].find('\n'), std::string::npos) << lines[l];
    EXPECT_THAT(lines[l], HasSubstr(measured.levels[l].label));
  }
  const std::string summary = Joined(lines) + Joined(CrossLevelSummaryLines(measured));
  const std::string warnings = Joined(measured.warnings);
  EXPECT_FALSE(HasUndefinedNumber(summary)) << summary;
  EXPECT_FALSE(HasUndefinedNumber(warnings)) << warnings;
  // The clean level has its numbers; the one below the mode says why it has none.
  EXPECT_THAT(lines[0], HasSubstr("f = "));
  EXPECT_THAT(lines[0], Not(HasSubstr("not estimated")));
  EXPECT_THAT(lines[3], HasSubstr("phase resonance not estimated (the response never crosses quadrature"));
  EXPECT_THAT(lines[2], HasSubstr("not estimated ("));
  // A flat sweep has no phase resonance, no peak and so no ζ it could stand behind.
  EXPECT_THAT(lines[2], HasSubstr("phase resonance not estimated ("));

  // The page, from the file as `beamid report` reads it (JSON null back as NaN).
  const MeasuredBackboneFile file = ReadMeasuredBackboneFile(folder / "out.json");
  const std::string page = MeasuredBackboneHtmlReport(file, "out.json");
  std::smatch found;
  if (std::regex_search(page, found, std::regex("(^|[^a-z])(nan|inf|infinity)([^a-z]|$)", std::regex::icase)))
    ADD_FAILURE() << "an undefined number on the page: …"
                  << page.substr(std::max<long>(0, found.position(0) - 200), 400) << "…";
  EXPECT_THAT(page, HasSubstr("not estimated"));
  EXPECT_THAT(page, HasSubstr("the response never crosses quadrature"));
  std::filesystem::remove_all(folder);
}

TEST(MeasuredBackboneSummary, AFlagRepeatedReadsOnceWithItsCount) {
  LevelResonance level;
  level.label = "high";
  for (int i = 0; i < 3; ++i) level.flags.push_back({.kind = LevelFlagKind::kJump, .quantity = "sweep"});
  level.flags.push_back({.kind = LevelFlagKind::kCoarseSteps, .quantity = "half_power_damping_ratio"});
  level.in_global_fit = false;
  EXPECT_EQ(FlagWords(level), "[jump ×3] [coarse steps] [left out of the fit]");
  EXPECT_EQ(level.FlagNote("sweep"), "[FLAG: jump ×3]");
  MeasuredBackbone measured;
  measured.levels = {level, LevelResonance{.label = "low"}};
  const std::vector<std::string> lines = LevelSummaryLines(measured);
  ASSERT_EQ(lines.size(), 2u);
  EXPECT_THAT(lines[0], HasSubstr("[jump ×3] [coarse steps] [left out of the fit]"));
  EXPECT_THAT(lines[1], Not(HasSubstr("[")));
  EXPECT_FALSE(HasUndefinedNumber(Joined(lines) + Joined(CrossLevelSummaryLines(measured))));
}

}  // namespace
}  // namespace beamid::solver
