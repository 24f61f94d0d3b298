// The report's account of the recording: a step the extraction
// found cut before it settled and a step the robust fit left out are circled
// on the frequency response plot and listed in "The recording" with the
// parameters without and with them; when the diagnosis blames the
// recording, its fault and what to do on the rig come before the candidates.
#include "solver/report/html_report.h"

#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "tests/support/sample_report.h"

namespace beamid::solver {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;

ReportInput Input() {
  ReportInput input;
  input.result_file = "out/result.json";
  input.campaign_folder = "campaign";
  ResultFile& r = input.result;
  r.model.fit_channels = {"acc1"};
  r.parameters = {{.name = "k1", .unit = "N*m/rad", .value = 150.003, .std = 0.002, .lower_95 = 149.999,
                   .upper_95 = 150.007}};
  r.robust_fit = ResultRobustFit{
      .applied = true,
      .note = "left out 1 outlying step(s) and refitted: high 55 Hz",
      .outliers = {{.level = "high", .file = "high/step_020.csv", .frequency_hz = 55.0, .chi_square = 1.17e4,
                    .num_residuals = 12}},
      .ordinary_parameters = {{.name = "k1", .unit = "N*m/rad", .value = 150.417}}};
  return input;
}

ReportCurves Curves() {
  ReportCurves curves;
  curves.channels = {{.channel = "acc1", .position_m = 0.1, .si_unit = "m/s^2", .fitted = true}};
  LevelCurves level{.level = "high", .force_amplitude_N = 9.0};
  const double frequencies[] = {54.5, 54.75, 55.0, 55.25};
  for (double f : frequencies)
    level.measured.push_back({.frequency_hz = f, .amplitude = {10.0 + f - 54.0},
                              .file = "high/step_0" + std::to_string(static_cast<int>(4 * f) - 200) + ".csv"});
  level.measured[2].file = "high/step_020.csv";
  level.measured[2].flag = "recorded before it settled; left out by the robust fit";
  for (double f = 54.0; f <= 56.0; f += 0.5) level.model.push_back({.frequency_hz = f, .amplitude = {12.0}});
  curves.levels = {level};
  // The other plots need something to draw.
  for (double f = 54.0; f <= 56.0; f += 0.5) curves.backbone.push_back({.frequency_hz = f, .amplitude = 5.0 + f - 54.0});
  curves.residuals = testing::UnitResidualMap(level);
  return curves;
}

TEST(HtmlReportRecording, CirclesAndListsTheFlaggedStepsWithTheParametersWithoutAndWithThem) {
  const std::string page = HtmlReport(Input(), Curves());
  EXPECT_THAT(page, HasSubstr("<h2>The recording</h2>"));
  EXPECT_THAT(page, HasSubstr("high 55 Hz (<code>high/step_020.csv</code>): recorded before it settled; left out by "
                              "the robust fit"));
  EXPECT_THAT(page, HasSubstr("flagged step (see the recording section)"));  // the plot's legend
  // Both at the reported value's σ (0.002): four decimals.
  EXPECT_THAT(page, HasSubstr("<tr><td>k1</td><td>150.0030</td><td>150.4170</td></tr>"));
  // No flagged step, no robust fit: nothing to say.
  ReportInput clean = Input();
  clean.result.robust_fit.reset();
  ReportCurves settled = Curves();
  settled.levels[0].measured[2].flag.clear();
  const std::string quiet = HtmlReport(clean, settled);
  EXPECT_THAT(quiet, Not(HasSubstr("The recording")));
  EXPECT_THAT(quiet, Not(HasSubstr("flagged step")));
}

TEST(HtmlReportRecording, ADiagnosisThatBlamesTheRecordingSaysWhatToDoBeforeTheCandidates) {
  ReportInput input = Input();
  DiagnosisResult d;
  d.verdict = DiagnosisVerdict::kCauseNamed;
  d.selected = {"sensor_gain(acc2)"};
  d.blame = Blame::kRecording;
  d.summary = "A fault of the recording, not of the model: sensor_gain(acc2).";
  d.location_error = "not located";
  CandidateOutcome gain{.name = "sensor_gain(acc2)", .rig_check = "check acc2's calibration: it reads 5.0 % high",
                        .status = RefitStatus::kRefitted, .significant = true, .measurement = true};
  CandidateOutcome friction{.name = "support_friction", .status = RefitStatus::kRefitted};
  d.candidates = {gain, friction};
  input.diagnosis = DiagnosisFile{.diagnosis = d};
  const std::string page = HtmlReport(input, Curves());
  EXPECT_THAT(page, HasSubstr("to blame: <b>the recording</b>"));
  const auto action = page.find("check acc2&#39;s calibration: it reads 5.0 % high");
  const auto candidates = page.find("<h3>Candidates");
  ASSERT_NE(action, std::string::npos) << page.substr(0, 2000);
  ASSERT_NE(candidates, std::string::npos);
  EXPECT_LT(action, candidates);
  EXPECT_THAT(page, HasSubstr("<td>sensor_gain(acc2)</td><td>recording</td>"));
  EXPECT_THAT(page, HasSubstr("<td>support_friction</td><td>physics</td>"));
}

}  // namespace
}  // namespace beamid::solver
