// The HTML page of a measured backbone on its own
// (solver/report/measured_backbone_report.h): every level with its numbers,
// its flags next to the number they concern and in full below the table,
// its jumps, whether it entered the cross-level fit, the damping trend's
// verdict, the warnings and the two plots (gnuplot SVG); the user's texts
// escaped, nothing loaded from outside the page.
#include "solver/report/measured_backbone_report.h"

#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

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

}  // namespace
}  // namespace beamid::solver
