// What the report says follows the outcome it shows: the damping caption
// says what the measured backbone concluded (each verdict, with its own z),
// the parameter table leads with the damping law the data accept, and a
// candidate that was not refitted (or whose refit failed) says so instead
// of showing a χ², drop and p it never had.
#include "solver/report/html_report.h"

#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "solver/estimation/damping_laws.h"
#include "tests/support/sample_report.h"

namespace beamid::solver {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;

ParameterEstimate Estimate(const std::string& name, double value, double std) {
  return {.name = name, .unit = "N*m*s/rad", .value = value, .std = std, .lower_95 = value - 1.96 * std,
          .upper_95 = value + 1.96 * std};
}

ReportInput Input() {
  ReportInput input;
  input.result_file = "out/result.json";
  input.campaign_folder = "campaign";
  input.result.model.fit_channels = {"acc1"};
  input.result.parameters = {{.name = "c", .unit = "N*m*s/rad", .value = 0.0465, .std = 0.0005,
                              .lower_95 = 0.0465 - 1.96 * 0.0005, .upper_95 = 0.0465 + 1.96 * 0.0005}};
  input.result.fit.reduced_chi_square = 1.6;
  return input;
}

ReportCurves Curves(Trend trend, double z, bool damping = true) {
  return testing::MinimalReportCurves(trend, z, damping);
}

TEST(HtmlReportCaptions, TheDampingCaptionSaysTheMeasuredBackbonesVerdictWithItsOwnZ) {
  const std::string rises = HtmlReport(Input(), Curves(Trend::kRises, 10.5));
  EXPECT_THAT(rises, HasSubstr("against amplitude rises beyond a constant damper (+10.5 σ)"));
  EXPECT_THAT(rises, Not(HasSubstr("consistent with a constant damper")));
  const std::string falls = HtmlReport(Input(), Curves(Trend::kFalls, -11.6));
  EXPECT_THAT(falls, HasSubstr("against amplitude falls below a constant damper (-11.6 σ)"));
  const std::string none = HtmlReport(Input(), Curves(Trend::kNone, 0.4));
  EXPECT_THAT(none, HasSubstr("against amplitude is consistent with a constant damper (+0.4 σ)"));
  EXPECT_THAT(none, Not(HasSubstr("rises beyond")));
}

TEST(HtmlReportCaptions, WhenTheDataRejectTheLossFactorTheAcceptedLawsParametersLead) {
  ReportInput input = Input();
  input.result.damping_laws.laws = {DampingLawFitOf("loss_factor", {Estimate("c", 0.0465, 0.0005)}, 160.0, 100),
                                    DampingLawFitOf("rayleigh", {Estimate("c", 0.0501, 0.0006)}, 100.0, 99)};
  JudgeDampingLaws(&input.result.damping_laws);
  const std::string page = HtmlReport(input, Curves(Trend::kNone, 0.0));
  // Values rounded to their σ (0.0006, 0.0005): five decimals.
  const auto answer = page.find("<td>0.05010</td>");
  const auto rejected = page.find("<td>0.04650</td>");
  ASSERT_NE(answer, std::string::npos) << "the accepted law's c";
  ASSERT_NE(rejected, std::string::npos) << "the rejected law's c, for comparison";
  EXPECT_LT(answer, rejected) << "the answer comes first";
  EXPECT_THAT(page, HasSubstr("reject the loss factor"));
  EXPECT_THAT(page, HasSubstr("<b>rayleigh</b>"));

  // Accepted: one table, the fit's own.
  ReportInput accepted = Input();
  accepted.result.damping_laws.laws = {DampingLawFitOf("loss_factor", {Estimate("c", 0.0465, 0.0005)}, 100.5, 100),
                                       DampingLawFitOf("rayleigh", {Estimate("c", 0.0466, 0.0006)}, 100.0, 99)};
  JudgeDampingLaws(&accepted.result.damping_laws);
  const std::string kept = HtmlReport(accepted, Curves(Trend::kNone, 0.0));
  EXPECT_THAT(kept, Not(HasSubstr("reject the loss factor")));
  EXPECT_THAT(kept, Not(HasSubstr("<td>0.04660</td>")));
}

TEST(HtmlReportCaptions, ACandidateNotRefittedOrFailedSaysSoInsteadOfNumbers) {
  ReportInput input = Input();
  DiagnosisResult d;
  d.verdict = DiagnosisVerdict::kCauseNamed;
  d.selected = {"support_friction"};
  d.base.chi_square = 4.5e5;
  CandidateOutcome friction{.name = "support_friction", .status = RefitStatus::kRefitted, .p_value = 1e-30,
                            .residual_drop = 4.5e4, .significant = true};
  friction.fit.chi_square = 10.0;
  CandidateOutcome skipped{.name = "added_mass", .status = RefitStatus::kNotRefitted,
                           .status_message = "support_friction already fits within the noise"};
  CandidateOutcome failed{.name = "clamp_compliance", .status = RefitStatus::kFailed,
                          .status_message = "maximum number of iterations reached"};
  d.candidates = {friction, skipped, failed};
  input.diagnosis = DiagnosisFile{.diagnosis = d};
  const std::string page = HtmlReport(input, Curves(Trend::kNone, 0.0));
  EXPECT_THAT(page, HasSubstr("<td colspan=\"4\">not refitted: support_friction already fits within the noise</td>"));
  EXPECT_THAT(page, HasSubstr("<td colspan=\"4\">refit failed: maximum number of iterations reached</td>"));
  EXPECT_THAT(page, Not(HasSubstr("refit failed: not refitted")));
}

// A diagnosis that names a cause: its model's parameters lead (the base
// fit's beside them), its first harmonic is drawn at the steps beside the
// base model's, and the held-out channel gets measured, base and selected.
TEST(HtmlReportCaptions, ADiagnosisThatNamesACauseShowsTheSelectedModelBesideTheBase) {
  ReportInput input = Input();
  DiagnosisResult d;
  d.verdict = DiagnosisVerdict::kCauseNamed;
  d.selected = {"support_friction"};
  d.base.parameters = {Estimate("c", 0.0465, 0.0005)};
  d.final_fit.parameters = {Estimate("c", 0.0412, 0.0004), Estimate("jenkins_stiffness", 50.04, 0.01)};
  for (double f : {54.5, 55.0, 55.5})
    for (const char* channel : {"acc1", "acc3"})
      d.response.push_back({.level = "high", .frequency_hz = f, .channel = channel, .held_out = channel[3] == '3',
                            .measured = {6.2, 0.0}, .base_model = {3.5, 0.0}, .final_model = {6.1, 0.0}});
  input.diagnosis = DiagnosisFile{.diagnosis = d};
  const std::string page = HtmlReport(input, Curves(Trend::kNone, 0.0));
  const auto selected = page.find("The selected model: support_friction");
  const auto base = page.find("The base model's fit (identify), which the diagnosis rejects");
  ASSERT_NE(selected, std::string::npos);
  ASSERT_NE(base, std::string::npos);
  EXPECT_LT(selected, base);
  EXPECT_THAT(page, HasSubstr("<tr><td>c</td><td>0.04120</td><td>0.00040</td>"));          // rounded to its σ
  EXPECT_THAT(page, HasSubstr("<td>N·m·s/rad</td><td>0.04650&nbsp;± 0.00050</td></tr>"));  // the base fit's c beside it
  EXPECT_THAT(page, HasSubstr("selected model (support_friction) high"));  // on the response curves
  EXPECT_THAT(page, HasSubstr("id=\"held-out-selected-acc3\""));
  EXPECT_THAT(page, Not(HasSubstr("id=\"held-out-selected-acc1\"")));  // acc1 was fitted

  // No cause named: no selected model anywhere.
  d.verdict = DiagnosisVerdict::kNoSignificantDiscrepancy;
  d.selected = {"none"};
  input.diagnosis = DiagnosisFile{.diagnosis = d};
  const std::string none = HtmlReport(input, Curves(Trend::kNone, 0.0));
  EXPECT_THAT(none, Not(HasSubstr("selected model")));
  EXPECT_THAT(none, HasSubstr("<h2>Identified parameters</h2>"));
}

}  // namespace
}  // namespace beamid::solver
