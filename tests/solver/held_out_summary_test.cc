// A held-out channel whose measurements resolve no error on a harmonic (all
// of them below the noise floor) has no worst error there: result.json
// stores null with a step count of 0, and identify and the report say
// "nothing measurable", never "0.00 %".
#include <cmath>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "solver/estimation/fit_data.h"
#include "solver/estimation/identification_problem.h"
#include "solver/estimation/identify.h"
#include "solver/estimation/model_structure.h"
#include "solver/estimation/result_file.h"
#include "solver/estimation/result_io.h"
#include "solver/report/held_out_summary.h"
#include "tests/support/synthetic_fit_data.h"

namespace beamid::solver {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;

// The synthetic data's 3rd harmonic (4e-4 of the fundamental) lies 25 times
// below its σ of 0.01: no step resolves an error there; the fundamental
// (|X_1| ≈ 2.2, σ 0.01) is resolved at every step.
TEST(HeldOutSummary, AHarmonicNoStepResolvesIsNothingMeasurableNotZero) {
  const FitData fit = testing::SyntheticFitData();
  const ModelStructure structure = PolynomialModel({.k1_Nm_rad = 100.0});
  IdentificationProblem problem(fit, structure, {});
  IdentifyResult result;
  result.x = problem.FeasiblePoint(structure.Values());
  const ResultFile file = MakeResultFile(fit, fit, problem, result, {});
  ASSERT_EQ(file.validation.size(), 2u);
  const HeldOutChannel& acc1 = file.validation[0];
  EXPECT_EQ(acc1.measurable_steps_h1, 3);
  EXPECT_TRUE(std::isfinite(acc1.worst_h1_relative_error));
  EXPECT_EQ(acc1.measurable_steps_h3, 0);
  EXPECT_TRUE(std::isnan(acc1.worst_h3_relative_error)) << acc1.worst_h3_relative_error;

  const std::string text = HeldOutSummary(acc1);
  EXPECT_THAT(text, HasSubstr("on the 1st harmonic (over the 3 of 3 steps that resolve it)"));
  EXPECT_THAT(text, HasSubstr("nothing measurable on the 3rd harmonic (none of the 3 steps resolves its error"));
  EXPECT_THAT(text, Not(HasSubstr("nan")));

  // Stored as null, read back as NaN with its count of 0.
  const std::string json = ResultFileToJson(file);
  EXPECT_THAT(json, HasSubstr("\"worst_h3_relative_error\": null"));
  const ResultFile read = ResultFileFromJson(json, "result.json");
  EXPECT_TRUE(std::isnan(read.validation[0].worst_h3_relative_error));
  EXPECT_EQ(read.validation[0].measurable_steps_h3, 0);
  EXPECT_EQ(HeldOutSummary(read.validation[0]), text);
}

// A file written before the NaN holds 0 there: the count still tells.
TEST(HeldOutSummary, AnOlderFilesZeroWithNoStepIsNothingMeasurable) {
  const HeldOutChannel older{.channel = "acc3",
                             .worst_h1_relative_error = 0.0,
                             .worst_h3_relative_error = 0.0,
                             .measurable_steps_h1 = 0,
                             .measurable_steps_h3 = 0,
                             .steps = std::vector<HeldOutStep>(5)};
  const std::string text = HeldOutSummary(older);
  EXPECT_THAT(text, HasSubstr("nothing measurable on the 1st harmonic (none of the 5 steps"));
  EXPECT_THAT(text, HasSubstr("nothing measurable on the 3rd harmonic"));
  EXPECT_THAT(text, Not(HasSubstr("0.00 %")));
  const HeldOutChannel measured{.channel = "acc3",
                                .worst_h1_relative_error = 0.0123,
                                .worst_h3_relative_error = 0.2,
                                .measurable_steps_h1 = 1,
                                .measurable_steps_h3 = 4,
                                .steps = std::vector<HeldOutStep>(5)};
  EXPECT_EQ(HeldOutSummary(measured),
            "worst error 1.23 % on the 1st harmonic (over the 1 of 5 steps that resolve it); worst error 20.00 % on the "
            "3rd harmonic (over the 4 of 5 steps that resolve it)");
}

}  // namespace
}  // namespace beamid::solver
