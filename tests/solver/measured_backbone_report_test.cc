// The HTML page of a measured backbone on its own
// (solver/report/measured_backbone_report.h): every level with its numbers,
// its flags next to the number they concern and in full below the table,
// its jumps, whether it entered the cross-level fit, the damping trend's
// verdict, the warnings and the two plots (gnuplot SVG); per level one
// figure of its measured |X/F| and phase with the fit over them and the
// peak, half-power points, phase resonance and jumps marked
// (solver/report/level_frf_plot.h);
// the user's texts escaped, nothing loaded from outside the page.
#include "solver/report/measured_backbone_report.h"

#include <cmath>
#include <complex>
#include <numbers>
#include <string>

#include <gmock/gmock.h>
#include <fmt/core.h>
#include <gtest/gtest.h>

#include "solver/report/level_frf_plot.h"

namespace beamid::solver {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;

std::size_t Count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

Estimate Est(double value, double std) { return {.value = value, .std = std, .valid = true}; }

// One mode's X/F (1 kg, f_n 54 Hz, ζ 0.57 %) at 41 steps from 53 to 55 Hz,
// and the same curve, twice as dense, as the fit.
void AddCurves(LevelResonance& level) {
  const auto point = [](double f_hz) {
    const double wn = 2 * std::numbers::pi * 54.0, w = 2 * std::numbers::pi * f_hz;
    const std::complex<double> h = 1.0 / std::complex<double>(wn * wn - w * w, 2 * 0.0057 * wn * w);
    return LevelFrfPoint{.frequency_hz = f_hz, .receptance_m_N = std::abs(h), .phase_rad = std::arg(h)};
  };
  for (int i = 0; i <= 40; ++i) level.measured_frf.push_back(point(53.0 + 0.05 * i));
  for (int i = 0; i <= 80; ++i) level.fit_frf.push_back(point(53.0 + 0.025 * i));
}

MeasuredBackboneFile File() {
  MeasuredBackboneFile file;
  file.inputs = {"low.csv", "high.csv"};
  file.channel = "acc2";
  file.response_quantity = "acceleration";
  LevelResonance low;
  low.label = "low\" onmouseover=\"alert(1)";
  low.quadrature_frequency_hz = Est(54.0046, 2e-4);
  low.quadrature_amplitude_m = Est(2.9e-4, 2e-8);
  low.quadrature_damping_ratio = Est(0.0057, 1e-5);
  low.damping_ratio = Est(0.0057, 4e-5);
  low.local_damping_ratio = Est(0.00571, 1e-5);
  low.peak_frequency_hz = Est(53.9982, 1e-4);
  low.peak_receptance_m_N = Est(7.6e-5, 1e-8);
  low.half_power_lower_frequency_hz = Est(53.6925, 1e-4);
  low.half_power_upper_frequency_hz = Est(54.3094, 1e-4);
  low.half_power_damping_ratio = Est(0.0057, 2e-5);
  AddCurves(low);
  LevelResonance high;
  high.label = "high";
  high.quadrature_note = "the response crosses quadrature with the force only across a jump up";
  high.quadrature_amplitude_m = Est(2.6e-3, 1e-7);
  high.half_power_damping_ratio = Est(-0.001, 1e-4);
  high.jumps = {{.from_step = 30, .to_step = 31, .from_frequency_hz = 53.1, .to_frequency_hz = 53.0,
                 .up_sweep = false, .receptance_ratio = 2.5, .phase_change_rad = 1.0}};
  high.flags = {{.kind = LevelFlagKind::kJump, .quantity = "sweep", .message = "the response jumps <here>"},
                {.kind = LevelFlagKind::kDampingNotPositive, .quantity = "half_power_damping_ratio",
                 .message = "the half-power damping ratio is -0.1 %"}};
  high.in_global_fit = false;
  AddCurves(high);
  high.jumps.push_back({.from_step = 10, .to_step = 11, .from_frequency_hz = 53.5, .to_frequency_hz = 53.55,
                        .up_sweep = true, .receptance_ratio = 0.5, .phase_change_rad = -1.0});
  high.flags.push_back({.kind = LevelFlagKind::kJump, .quantity = "sweep", .message = "the response jumps again"});
  file.levels = {low, high};
  file.single_mode_fit.form = "wn^2: polynomial 2, zeta*wn: polynomial 1, A constant";
  for (int k = 0; k <= 10; ++k)
    file.single_mode_fit.curve.push_back({.amplitude_m = 2.9e-4 + 2e-4 * k,
                                          .frequency_hz = 54.0 + 0.05 * k,
                                          .frequency_std_hz = 0.002,
                                          .damping_ratio = 0.0057,
                                          .damping_ratio_std = 1e-4});
  file.damping_trend = {.verdict = Trend::kNone, .damping_ratio_verdict = Trend::kRises};
  file.warnings = {"level 'high' is flagged (jump: ...): left out of the cross-level fit"};
  return file;
}

TEST(MeasuredBackboneReport, ShowsEveryLevelItsFlagsAndTheTrend) {
  // The page without its plots, so that a failure prints what matters.
  const std::string page = MeasuredBackboneHtmlReport(File(), "out/measured.json");
  std::string html = page;
  for (std::size_t at; (at = html.find("<svg")) != std::string::npos;)
    html.replace(at, html.find("</svg>", at) + 6 - at, "[plot]");
  EXPECT_THAT(page, HasSubstr("<svg"));
  EXPECT_THAT(html, HasSubstr("54.0046"));
  EXPECT_THAT(html, HasSubstr("[FLAG: jump]"));
  EXPECT_THAT(html, HasSubstr("[FLAG: not positive]"));  // next to the half-power ζ
  EXPECT_THAT(html, HasSubstr("the response jumps &lt;here&gt;"));
  EXPECT_THAT(html, HasSubstr("down-sweep"));
  EXPECT_THAT(html, HasSubstr("only across a jump up"));
  EXPECT_THAT(html, HasSubstr("consistent with a constant damper"));
  EXPECT_THAT(html, HasSubstr("left out of the cross-level fit"));
  EXPECT_THAT(html, HasSubstr("1 left out of the"));
  EXPECT_THAT(html, HasSubstr("[plot]"));
  // The user's texts escaped; nothing loaded from outside.
  EXPECT_THAT(html, HasSubstr("low&quot; onmouseover=&quot;alert(1)"));
  EXPECT_THAT(html, Not(HasSubstr("onmouseover=\"")));
  // Nothing to run: the one script element is the JSON data block.
  EXPECT_EQ(Count(html, "<script"), 1u);
  EXPECT_THAT(html, HasSubstr("<script type=\"application/json\" id=\"beamid-report-data\">"));
  EXPECT_THAT(html, Not(HasSubstr(" src=")));
  EXPECT_THAT(html, Not(HasSubstr("<link")));
}

// The figures of the page, each cut at its own </figure>.
std::vector<std::string> LevelFigures(const std::string& page) {
  std::vector<std::string> figures;
  for (std::size_t at = page.find("<figure class=\"plot level-frf\""); at != std::string::npos;
       at = page.find("<figure class=\"plot level-frf\"", at + 1))
    figures.push_back(page.substr(at, page.find("</figure>", at) - at));
  return figures;
}

TEST(MeasuredBackboneReport, DrawsEachLevelsResponseWithTheFitAndItsMarkers) {
  const MeasuredBackboneFile file = File();
  const std::vector<std::string> figures = LevelFigures(MeasuredBackboneHtmlReport(file, "out/measured.json"));
  ASSERT_EQ(figures.size(), file.levels.size());
  for (const auto& figure : figures) {
    EXPECT_THAT(figure, HasSubstr("<svg"));
    EXPECT_THAT(figure, HasSubstr("measured steps"));  // the legend of the dots
    EXPECT_THAT(figure, HasSubstr("single-mode fit across levels"));
  }
  // low: a peak with both half-power points; high: two jumps, no peak.
  EXPECT_THAT(figures[0], HasSubstr("half-power points (peak/√2)"));
  EXPECT_THAT(figures[0], HasSubstr("53.6925"));
  EXPECT_THAT(figures[0], HasSubstr("phase resonance 54.0046"));
  EXPECT_THAT(figures[0], Not(HasSubstr("jump of the sweep")));
  EXPECT_THAT(figures[1], HasSubstr("jump of the sweep"));
  EXPECT_THAT(figures[1], HasSubstr("2 jumps of the sweep (dashed) <span class=\"flag\">[FLAG: jump ×2]</span>"));
  EXPECT_THAT(figures[1], Not(HasSubstr("half-power points (peak/√2)")));
}

TEST(MeasuredBackboneReport, TheLevelPlotMarksThePeakTheHalfPowerPointsAndEveryJump) {
  MeasuredBackboneFile file = File();
  const LevelResonance& low = file.levels[0];
  const std::string low_data = LevelFrfPlot(low, LabelsOf("force")).datablocks;
  // The peak at its frequency and |X/F|; the half-power points at 1/√2 of it.
  EXPECT_THAT(low_data, HasSubstr("$peak << EOD\n53.9982 7.6e-05\nEOD"));
  EXPECT_THAT(low_data, HasSubstr(fmt::format("$half_power << EOD\n53.6925 {:.9g}\n54.3094 {:.9g}\nEOD",
                                              7.6e-5 / std::sqrt(2.0), 7.6e-5 / std::sqrt(2.0))));
  // The phase resonance on the phase panel, at −90° where the phase passes below zero.
  EXPECT_THAT(low_data, HasSubstr("$quadrature << EOD\n54.0046 -90\nEOD"));
  // Each jump a segment between the measured steps it joins (run order).
  const LevelResonance& high = file.levels[1];
  const StackedPlot plot = LevelFrfPlot(high, LabelsOf("force"));
  const std::size_t jumps = plot.datablocks.find("$jumps << EOD\n");
  ASSERT_NE(jumps, std::string::npos);
  const std::string block = plot.datablocks.substr(jumps, plot.datablocks.find("EOD\n", jumps + 14) - jumps);
  EXPECT_EQ(Count(block, "\n\n"), 2u) << block;  // two segments, each ended by a blank row
  EXPECT_THAT(block, HasSubstr(fmt::format("{:.9g} ", high.measured_frf[10].frequency_hz)));
  EXPECT_THAT(block, HasSubstr(fmt::format("{:.9g} ", high.measured_frf[11].frequency_hz)));
  EXPECT_THAT(plot.datablocks, Not(HasSubstr("$peak")));
  EXPECT_THAT(plot.datablocks, Not(HasSubstr("$quadrature")));  // not measured across the jump up
  // The fit drawn as a line on both panels, the measured steps as points.
  ASSERT_EQ(plot.panels.size(), 2u);
  std::string sources;
  for (const auto& panel : plot.panels)
    for (const auto& item : panel.items) sources += item.source + " " + item.style + "\n";
  EXPECT_THAT(sources, HasSubstr("$fit using 1:2 with lines"));
  EXPECT_THAT(sources, HasSubstr("$fit_phase using 1:2 with lines"));
  EXPECT_THAT(sources, HasSubstr("$measured using 1:3 with points"));
  EXPECT_THAT(sources, HasSubstr("$jumps using 1:3"));
  // A file written before the curves: no figure, the rest of the page as before.
  for (auto& level : file.levels) level.measured_frf.clear(), level.fit_frf.clear();
  EXPECT_TRUE(LevelFigures(MeasuredBackboneHtmlReport(file, "old.json")).empty());
}

}  // namespace
}  // namespace beamid::solver
