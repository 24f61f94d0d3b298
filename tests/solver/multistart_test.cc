// The distinct minima of a multistart search and whether the data decide
// between the best two (solver/multistart.h), on hand-made start outcomes.
#include "solver/estimation/multistart.h"

#include <gtest/gtest.h>

namespace beamid::solver {
namespace {

StartOutcome Converged(std::vector<double> parameters, double chi_square) {
  return {.parameters = std::move(parameters), .objective = 0.5 * chi_square, .success = true};
}

const std::vector<ParameterBounds> kBounds = {{.typical = 100.0}, {.typical = 1e5}};

TEST(SummarizeMinima, GroupsStartsThatEndedAtTheSameMinimumBestFirst) {
  const std::vector<StartOutcome> starts = {
      Converged({150.7, 3.23e5}, 1.8e8), Converged({150.0, 3.0e5}, 108.0),
      Converged({150.0 * (1 + 1e-6), 3.0e5}, 108.0 * (1 + 1e-7)),
      {.parameters = {1.0, 1.0}, .objective = 1.0, .success = false}};  // not converged: ignored, however low
  const MinimaSummary summary = SummarizeMinima(starts, kBounds, 100);
  ASSERT_EQ(summary.minima.size(), 2u);
  EXPECT_DOUBLE_EQ(summary.minima[0].chi_square, 108.0);
  EXPECT_EQ(summary.minima[0].num_starts, 2);
  EXPECT_EQ(summary.minima[1].num_starts, 1);
  // The fit is worse than the noise (χ²/ν = 1.08): the gap is in its units.
  EXPECT_NEAR(summary.second_chi_square_gap, (1.8e8 - 108.0) / 1.08, 1e-6 * 1.8e8);
  EXPECT_TRUE(summary.decisive);
}

TEST(SummarizeMinima, SameMisfitButOtherParametersIsAnotherMinimum) {
  const MinimaSummary summary =
      SummarizeMinima({Converged({150.0, 3.0e5}, 50.0), Converged({150.0, 3.1e5}, 50.0)}, kBounds, 100);
  ASSERT_EQ(summary.minima.size(), 2u);
  EXPECT_DOUBLE_EQ(summary.second_chi_square_gap, 0.0);
  EXPECT_FALSE(summary.decisive);
}

TEST(SummarizeMinima, AGapBelowTheThresholdIsNotDecisiveAndAboveItIs) {
  // Within the noise (χ²/ν < 1) the gap is the χ² difference itself.
  const auto gap = [](double second) {
    return SummarizeMinima({Converged({150.0, 3.0e5}, 80.0), Converged({140.0, 2.0e5}, second)}, kBounds, 100);
  };
  EXPECT_FALSE(gap(80.0 + 8.9).decisive);
  EXPECT_TRUE(gap(80.0 + 9.1).decisive);
  EXPECT_NEAR(gap(85.0).second_chi_square_gap, 5.0, 1e-12);
}

TEST(SummarizeMinima, NothingConvergedGivesNoMinimum) {
  const MinimaSummary summary = SummarizeMinima({{.parameters = {1.0, 2.0}, .success = false}}, kBounds, 10);
  EXPECT_TRUE(summary.minima.empty());
  EXPECT_TRUE(summary.decisive);
}

}  // namespace
}  // namespace beamid::solver
