// The multiple-scales program refuses what its model cannot hold. Its
// derivatives (constraint Jacobian, gradient, Gauss–Newton Hessian, reduced
// residual Jacobian) are checked against differences with every family's in
// fit_problem_derivatives_test.cc.
#include "solver/estimation/multiple_scales_problem.h"

#include <stdexcept>

#include <gtest/gtest.h>

#include "tests/support/synthetic_fit_data.h"

namespace beamid::solver {
namespace {

// Any data will do.
FitData SyntheticData() { return testing::SyntheticFitData(); }

ModelStructure Structure() {
  ModelStructure structure = PolynomialModel({});
  structure.linear.push_back(LossFactor());
  return structure;
}

TEST(MultipleScalesProblem, RefusesWhatTheModelCannotHold) {
  FitData with_masses = SyntheticData();
  with_masses.sensor_masses.point_masses.push_back({.position_m = 0.1, .mass_kg = 0.005});
  EXPECT_THROW(MultipleScalesProblem(with_masses, Structure()), std::invalid_argument);
  FitData five_harmonics = SyntheticData();
  five_harmonics.num_fit_harmonics = 5;
  EXPECT_THROW(MultipleScalesProblem(five_harmonics, Structure()), std::invalid_argument);
}

}  // namespace
}  // namespace beamid::solver
