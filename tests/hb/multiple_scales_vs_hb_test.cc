// The multiple-scales model against the exact harmonic balance of the
// continuous beam: they agree at small amplitude (first harmonic
// < 0.5 %), and the printed table documents how the error grows with the
// amplitude. HB is continued in force from the linear solution.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include <gtest/gtest.h>

#include "hb/harmonic_balance.h"
#include "hb/linear_beam.h"
#include "hb/multiple_scales.h"
#include "hb/support_law.h"
#include "tests/support/paper_setup.h"

namespace beamid::hb {
namespace {

constexpr double kSmallAmplitudeTolerance = 0.005;  // required: first harmonic < 0.5 %

struct Case {
  const char* name;
  PolynomialSupportLaw::Coefficients support;
  double frequency_ratio;  // Ω/ω0, on the single-valued part of the response
};

TEST(MultipleScalesVsHarmonicBalanceTest, AgreeAtSmallAmplitudeAndErrorGrowsWithAmplitude) {
  const std::vector<Case> cases = {
      {"cubic hardening", {.k1_Nm_rad = 150.0, .k2_Nm_rad2 = 0.0, .k3_Nm_rad3 = 1.0e5, .c_Nms_rad = 0.05}, 0.98},
      {"quadratic + cubic", {.k1_Nm_rad = 150.0, .k2_Nm_rad2 = 300.0, .k3_Nm_rad3 = 1.0e5, .c_Nms_rad = 0.05}, 0.98},
      {"cubic softening", {.k1_Nm_rad = 150.0, .k2_Nm_rad2 = 0.0, .k3_Nm_rad3 = -1.0e5, .c_Nms_rad = 0.05}, 1.02},
  };
  const std::vector<double> forces_N = {0.01, 0.1, 0.3, 1.0, 2.0, 4.0, 8.0, 16.0};
  const std::vector<double> positions(std::begin(testing::kSensorPositions_m), std::end(testing::kSensorPositions_m));
  for (const Case& c : cases) {
    const MultipleScalesModel model(testing::PaperBeam(), c.support, testing::kForcePosition_m);
    const LinearBeam beam(LinearBeamModel{testing::PaperBeam(), {}, c.support.k1_Nm_rad, c.support.c_Nms_rad},
                          testing::kForcePosition_m);
    const PolynomialSupportLaw law(c.support);
    const HarmonicBalance balance(beam, law, {.num_harmonics = 7});
    const double omega = c.frequency_ratio * model.NaturalFrequency_rad_s();
    std::printf("%s, Ω/ω0 = %.2f: relative error of MS vs HB (worst of x = 0.1, 0.3, 0.57 m; 0 = both exactly zero)\n", c.name,
                c.frequency_ratio);
    std::printf("  F [N]   |θ1| [rad]   |Y1(0.57)| [m]   H0 error   H1 error   H2 error   H3 error\n");
    Eigen::VectorXd previous;
    std::vector<double> first_harmonic_errors;
    for (double force : forces_N) {
      Eigen::VectorXcd force_phasors = Eigen::VectorXcd::Zero(2);
      force_phasors[1] = force;
      const HarmonicBalanceSolution exact = balance.Solve(omega, force_phasors, previous);
      ASSERT_TRUE(exact.converged) << c.name << " F = " << force;
      previous = HarmonicBalance::ToReal(exact.theta_rad);
      const Eigen::MatrixXcd y = balance.Displacements(exact, PadHarmonics(force_phasors, 7), positions);
      const std::vector<Complex> solutions = model.Solve(omega, force);
      ASSERT_EQ(solutions.size(), 1u) << c.name << " F = " << force;
      const bool even_harmonics = c.support.k2_Nm_rad2 != 0.0;
      double errors[4] = {0.0, 0.0, 0.0, 0.0};
      for (std::size_t p = 0; p < positions.size(); ++p) {
        const MultipleScalesModel::Harmonics h = model.Response(positions[p], solutions[0], omega, force);
        const Complex ms[4] = {h.h0_m, h.h1_m, h.h2_m, h.h3_m};
        for (int k = 0; k <= 3; ++k) {
          if (k % 2 == 0 && !even_harmonics) {
            // An odd law gives no even harmonics: both must (numerically) vanish.
            EXPECT_EQ(std::abs(ms[k]), 0.0);
            EXPECT_LT(std::abs(y(p, k)), 1e-12 * std::abs(y(p, 1)));
            continue;
          }
          errors[k] = std::max(errors[k], std::abs(ms[k] - y(p, k)) / std::abs(y(p, k)));
        }
      }
      std::printf("  %5.2f   %.3e    %.3e        %.2e   %.2e   %.2e   %.2e\n", force, std::abs(exact.theta_rad[1]),
                  std::abs(y(2, 1)), errors[0], errors[1], errors[2], errors[3]);
      first_harmonic_errors.push_back(errors[1]);
      if (force <= 0.1) {
        // Small amplitude: every harmonic the model carries is right.
        EXPECT_LT(errors[1], kSmallAmplitudeTolerance) << c.name << " F = " << force;
        for (int k : {0, 2, 3}) EXPECT_LT(errors[k], kSmallAmplitudeTolerance) << c.name << " H" << k;
      }
    }
    // Multiple scales is an expansion in the amplitude: its error must grow
    // (as a², the first neglected order).
    for (std::size_t i = 1; i < first_harmonic_errors.size(); ++i)
      EXPECT_GT(first_harmonic_errors[i], first_harmonic_errors[i - 1]) << c.name;
  }
}

}  // namespace
}  // namespace beamid::hb
