// The judgement of the damping laws (solver/estimation/damping_laws.h) on
// hand-made fits: which laws the data accept (the likelihood-ratio margin,
// scaled by a misfit beyond the noise), the model-form envelope over the
// accepted ones, and the flag of a parameter that depends on the law.
#include "solver/estimation/damping_laws.h"

#include <gtest/gtest.h>

namespace beamid::solver {
namespace {

ParameterEstimate Estimate(const std::string& name, double value, double std) {
  return {.name = name, .unit = "u", .value = value, .std = std, .lower_95 = value - 1.96 * std,
          .upper_95 = value + 1.96 * std};
}

DampingLawFit Law(const std::string& law, double c, double chi_square, int dof, const std::string& damping) {
  return DampingLawFitOf(law, {Estimate("k1", 150.0, 0.01), Estimate("c", c, 0.001), Estimate(damping, 1e-3, 1e-4)},
                         chi_square, dof);
}

const ModelFormInterval& IntervalOf(const DampingLawEnvelope& e, const std::string& name) {
  for (const auto& i : e.intervals)
    if (i.name == name) return i;
  throw std::runtime_error("no interval " + name);
}

TEST(DampingLaws, ALawTheDataRuleOutLeavesTheEnvelopeAndItsParametersAreFlagged) {
  DampingLawEnvelope e{.laws = {Law("loss_factor", 0.046, 160.0, 100, "loss_factor"),
                                Law("rayleigh", 0.050, 100.0, 99, "rayleigh_mass_1_s")}};
  JudgeDampingLaws(&e);
  EXPECT_FALSE(e.laws[0].accepted);  // 60 worse in χ², at χ²/ν ≈ 1
  EXPECT_TRUE(e.laws[1].accepted);
  ASSERT_EQ(e.intervals.size(), 2u);  // k1 and c; no damping parameter
  const ModelFormInterval& c = IntervalOf(e, "c");
  EXPECT_DOUBLE_EQ(c.lower_95, 0.050 - 1.96 * 0.001);  // the accepted law's alone
  EXPECT_DOUBLE_EQ(c.upper_95, 0.050 + 1.96 * 0.001);
  EXPECT_TRUE(c.depends_on_damping_law);  // 0.050 lies outside 0.046 ± 0.00196
  EXPECT_FALSE(IntervalOf(e, "k1").depends_on_damping_law);
}

// The answer is the accepted law's fit: the assumed one while the data
// accept it, else the accepted law that fits best.
TEST(DampingLaws, TheAnswerIsTheAssumedLawUntilTheDataRejectItThenTheBestAcceptedLaw) {
  EXPECT_EQ(AnswerLaw(DampingLawEnvelope{}), nullptr);
  DampingLawEnvelope rejected{.laws = {Law("loss_factor", 0.046, 160.0, 100, "loss_factor"),
                                       Law("mass_proportional", 0.049, 104.0, 100, "rayleigh_mass_1_s"),
                                       Law("rayleigh", 0.050, 100.0, 99, "rayleigh_mass_1_s")}};
  JudgeDampingLaws(&rejected);
  ASSERT_NE(AnswerLaw(rejected), nullptr);
  EXPECT_EQ(AnswerLaw(rejected)->law, "rayleigh");
  DampingLawEnvelope accepted{.laws = {Law("loss_factor", 0.05, 101.0, 100, "loss_factor"),
                                       Law("rayleigh", 0.05, 100.0, 99, "rayleigh_mass_1_s")}};
  JudgeDampingLaws(&accepted);
  EXPECT_EQ(AnswerLaw(accepted), &accepted.laws[0]);  // accepted, though rayleigh's χ² is lower
}

TEST(DampingLaws, LawsWithinTheMarginAreAllAcceptedAndTheEnvelopeSpansThem) {
  DampingLawEnvelope e{.laws = {Law("loss_factor", 0.0500, 100.0, 100, "loss_factor"),
                                Law("rayleigh", 0.0505, 95.0, 99, "rayleigh_mass_1_s")}};
  JudgeDampingLaws(&e);
  EXPECT_TRUE(e.laws[0].accepted);  // 5 < 6.63 worse
  EXPECT_TRUE(e.laws[1].accepted);
  const ModelFormInterval& c = IntervalOf(e, "c");
  EXPECT_DOUBLE_EQ(c.lower_95, 0.0500 - 1.96 * 0.001);
  EXPECT_DOUBLE_EQ(c.upper_95, 0.0505 + 1.96 * 0.001);
  EXPECT_FALSE(c.depends_on_damping_law);  // 0.0505 inside 0.05 ± 0.00196
}

TEST(DampingLaws, AMisfitBeyondTheNoiseWidensTheMarginByTheReducedChiSquare) {
  // Best χ²/ν = 4: a law 20 worse is 5 in units of the scatter, accepted;
  // 40 worse (10) is not.
  DampingLawEnvelope e{.laws = {Law("loss_factor", 0.05, 420.0, 100, "loss_factor"),
                                Law("rayleigh", 0.05, 400.0, 100, "rayleigh_mass_1_s"),
                                Law("stiffness_proportional", 0.05, 440.0, 100, "rayleigh_stiffness_s")}};
  JudgeDampingLaws(&e);
  EXPECT_TRUE(e.laws[0].accepted);
  EXPECT_TRUE(e.laws[1].accepted);
  EXPECT_FALSE(e.laws[2].accepted);
}

TEST(DampingLaws, AFailedRefitIsNeverAcceptedNorInTheEnvelope) {
  DampingLawEnvelope e{.laws = {Law("loss_factor", 0.05, 100.0, 100, "loss_factor"),
                                {.law = "rayleigh", .status = "failed: restoration phase failed"}}};
  JudgeDampingLaws(&e);
  EXPECT_TRUE(e.laws[0].accepted);
  EXPECT_FALSE(e.laws[1].accepted);
  EXPECT_DOUBLE_EQ(IntervalOf(e, "c").upper_95, 0.05 + 1.96 * 0.001);
}

TruncationRefit Truncation(double k1, double c) {
  return {.model_harmonics = 5,
          .refit_harmonics = 9,
          .converged = true,
          .status = "solved",
          .parameters = {Estimate("k1", k1, 0.01), Estimate("c", c, 0.001), Estimate("loss_factor", 1e-3, 1e-4)}};
}

// The total interval: the envelope over the accepted laws, widened on both
// sides by the truncation refit's shift, with its parts kept apart.
TEST(DampingLaws, TheTotalIntervalWidensTheEnvelopeByTheTruncationShiftOnBothSides) {
  DampingLawEnvelope e{.laws = {Law("loss_factor", 0.0500, 100.0, 100, "loss_factor"),
                                Law("rayleigh", 0.0505, 95.0, 99, "rayleigh_mass_1_s")},
                       .truncation = Truncation(150.03, 0.0499)};
  JudgeDampingLaws(&e);
  const ModelFormInterval& c = IntervalOf(e, "c");
  EXPECT_DOUBLE_EQ(c.statistical_lower_95, 0.0500 - 1.96 * 0.001);
  EXPECT_DOUBLE_EQ(c.damping_law_upper_95, 0.0505 + 1.96 * 0.001);
  EXPECT_NEAR(c.truncation_shift, -0.0001, 1e-15);
  EXPECT_NEAR(c.lower_95, 0.0500 - 1.96 * 0.001 - 0.0001, 1e-15);
  EXPECT_NEAR(c.upper_95, 0.0505 + 1.96 * 0.001 + 0.0001, 1e-15);
  EXPECT_NEAR(c.WidthRatio(), (0.0005 + 2 * 1.96 * 0.001 + 0.0002) / (2 * 1.96 * 0.001), 1e-12);
  EXPECT_FALSE(c.depends_on_truncation);  // 0.0499 inside 0.05 ± 0.00196
  const ModelFormInterval& k1 = IntervalOf(e, "k1");
  EXPECT_TRUE(k1.depends_on_truncation);  // 150.03 outside 150 ± 0.0196
  EXPECT_NEAR(k1.upper_95 - k1.lower_95, 2 * 1.96 * 0.01 + 2 * 0.03, 1e-12);
  EXPECT_EQ(TotalIntervalParts(e),
            "the statistical part (with the residual model error where the weighting estimates it), the accepted "
            "damping laws (loss_factor, rayleigh), the harmonic truncation (5 → 9 harmonics)");
}

// A truncation refit that failed adds nothing, and the headline says the
// intervals lack it rather than implying they hold it.
TEST(DampingLaws, AFailedTruncationRefitAddsNoShiftAndTheHeadlineSaysSo) {
  TruncationRefit failed = Truncation(151.0, 0.06);
  failed.converged = false;
  failed.status = "failed: maximum number of iterations exceeded";
  DampingLawEnvelope e{.laws = {Law("loss_factor", 0.05, 100.0, 100, "loss_factor")}, .truncation = failed};
  JudgeDampingLaws(&e);
  EXPECT_DOUBLE_EQ(IntervalOf(e, "k1").truncation_shift, 0.0);
  EXPECT_DOUBLE_EQ(IntervalOf(e, "k1").upper_95, 150.0 + 1.96 * 0.01);
  EXPECT_NE(TotalIntervalParts(e).find("NOT the harmonic truncation"), std::string::npos) << TotalIntervalParts(e);
  e.truncation.reset();
  JudgeDampingLaws(&e);
  EXPECT_NE(TotalIntervalParts(e).find("was not refitted"), std::string::npos) << TotalIntervalParts(e);
}

}  // namespace
}  // namespace beamid::solver
