// The diagnosis's verdict (solver/diagnosis/diagnosis.h, DecideVerdict) on
// hand-made candidate refits: the held-out channels overrule the in-sample
// ranking when they separate two significant candidates decisively, two
// candidates neither the fitted nor the held-out channels separate are named
// together as indistinguishable, and without held-out channels the in-sample
// BIC ranks; without a significant candidate, under propagated σ the
// misfit location's test alone decides whether the misfit is unexplained.
#include <limits>

#include <gtest/gtest.h>

#include "solver/diagnosis/diagnosis.h"

namespace beamid::solver {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

CandidateOutcome Candidate(const std::string& name, double chi_square, double held_out_chi_square) {
  CandidateOutcome c;
  c.name = name;
  c.status = RefitStatus::kRefitted;
  c.significant = true;
  c.fit.chi_square = chi_square;
  c.fit.degrees_of_freedom = 500;
  c.fit.num_residuals = 505;
  c.fit.reduced_chi_square = chi_square / 500.0;
  c.fit.bic = chi_square + 5.0 * std::log(505.0);
  c.fit.held_out_chi_square = held_out_chi_square;
  c.fit.held_out_num_residuals = 250;
  return c;
}

FitSummary MisfittingBase() {
  FitSummary base;
  base.chi_square = 20000.0;
  base.degrees_of_freedom = 501;
  base.reduced_chi_square = base.chi_square / base.degrees_of_freedom;
  return base;
}

TEST(DiagnosisVerdict, TheHeldOutChannelsOverruleTheInSampleRankingWhenTheySeparateDecisively) {
  // added_mass fits the fitted channels 6 % better, the modulus predicts the
  // held-out one 18x better (the campaign).
  const std::vector<CandidateOutcome> candidates = {Candidate("added_mass", 1300.0, 18000.0),
                                                    Candidate("modulus_error", 1380.0, 1000.0)};
  const Verdict v = DecideVerdict(MisfittingBase(), std::nullopt, PhasorUncertainty::kPropagated, candidates, {});
  EXPECT_EQ(v.verdict, DiagnosisVerdict::kCauseNamed);
  EXPECT_EQ(v.selected, std::vector<std::string>{"modulus_error"});
  EXPECT_EQ(v.ranking.front(), 1);
  EXPECT_EQ(v.ranked_by, RankedBy::kHeldOutChannels);
  EXPECT_EQ(v.tied_with, -1);
}

TEST(DiagnosisVerdict, TwoCandidatesNeitherChannelSetSeparatesAreNamedTogether) {
  // 2 apart in sample (χ²/ν 0.6: scale 1) and 3 apart held out: both within 6.63.
  const std::vector<CandidateOutcome> candidates = {Candidate("added_mass", 300.0, 260.0),
                                                    Candidate("modulus_error", 302.0, 257.0)};
  const Verdict v = DecideVerdict(MisfittingBase(), std::nullopt, PhasorUncertainty::kPropagated, candidates, {});
  EXPECT_EQ(v.verdict, DiagnosisVerdict::kCausesIndistinguishable);
  ASSERT_EQ(v.selected.size(), 2u);
  EXPECT_EQ(v.selected[0], "added_mass");  // the better BIC first: the held-out gap is not decisive
  EXPECT_EQ(v.selected[1], "modulus_error");
  EXPECT_EQ(v.tied_with, 1);
}

TEST(DiagnosisVerdict, AnInSampleGapAloneStillNamesOneCause) {
  const std::vector<CandidateOutcome> candidates = {Candidate("added_mass", 300.0, 260.0),
                                                    Candidate("modulus_error", 340.0, 258.0)};
  const Verdict v = DecideVerdict(MisfittingBase(), std::nullopt, PhasorUncertainty::kPropagated, candidates, {});
  EXPECT_EQ(v.verdict, DiagnosisVerdict::kCauseNamed);
  EXPECT_EQ(v.selected, std::vector<std::string>{"added_mass"});
}

TEST(DiagnosisVerdict, WithoutHeldOutChannelsTheInSampleBicRanksAndATieIsStillSaid) {
  std::vector<CandidateOutcome> candidates = {Candidate("clamp_compliance", 310.0, kNaN),
                                              Candidate("added_mass", 300.0, kNaN)};
  Verdict v = DecideVerdict(MisfittingBase(), std::nullopt, PhasorUncertainty::kPropagated, candidates, {});
  EXPECT_EQ(v.ranked_by, RankedBy::kInSampleBic);
  EXPECT_EQ(v.selected, std::vector<std::string>{"added_mass"});
  candidates[0].fit.chi_square = 303.0;
  candidates[0].fit.bic = 303.0 + 5.0 * std::log(505.0);
  v = DecideVerdict(MisfittingBase(), std::nullopt, PhasorUncertainty::kPropagated, candidates, {});
  EXPECT_EQ(v.verdict, DiagnosisVerdict::kCausesIndistinguishable);
}

TEST(DiagnosisVerdict, ASingleSignificantCandidateIsNamedAloneAndNoneLeavesTheBaseUnexplained) {
  std::vector<CandidateOutcome> candidates = {Candidate("support_friction", 300.0, 200.0),
                                              Candidate("added_mass", 301.0, 201.0)};
  candidates[1].significant = false;
  Verdict v = DecideVerdict(MisfittingBase(), std::nullopt, PhasorUncertainty::kPropagated, candidates, {});
  EXPECT_EQ(v.verdict, DiagnosisVerdict::kCauseNamed);
  EXPECT_EQ(v.selected, std::vector<std::string>{"support_friction"});
  candidates[0].significant = false;
  v = DecideVerdict(MisfittingBase(), std::nullopt, PhasorUncertainty::kPropagated, candidates, {});
  EXPECT_EQ(v.verdict, DiagnosisVerdict::kUnexplained);
  EXPECT_EQ(v.selected, std::vector<std::string>{"none"});
}

TEST(DiagnosisVerdict, UnderPropagatedSigmaTheLocationsTestAloneCallsAMisfitUnexplained) {
  // A base 1.5× its dof: within the acceptable reduced χ² of 4, beyond the
  // noise its σ state. No candidate explains it.
  FitSummary base;
  base.chi_square = 750.0;
  base.degrees_of_freedom = 500;
  base.reduced_chi_square = 1.5;
  std::vector<CandidateOutcome> candidates = {Candidate("added_mass", 740.0, kNaN)};
  candidates[0].significant = false;
  MisfitLocation location;
  location.significant = true;
  EXPECT_EQ(DecideVerdict(base, location, PhasorUncertainty::kPropagated, candidates, {}).verdict,
            DiagnosisVerdict::kUnexplained);
  // The relative floor's σ are no noise model: the base must also exceed 4.
  EXPECT_EQ(DecideVerdict(base, location, PhasorUncertainty::kRelativeFloor, candidates, {}).verdict,
            DiagnosisVerdict::kNoSignificantDiscrepancy);
  // A location that finds nothing: no discrepancy, whatever the base's reduced χ².
  location.significant = false;
  EXPECT_EQ(DecideVerdict(MisfittingBase(), location, PhasorUncertainty::kPropagated, candidates, {}).verdict,
            DiagnosisVerdict::kNoSignificantDiscrepancy);
}

}  // namespace
}  // namespace beamid::solver
