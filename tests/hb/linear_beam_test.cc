#include "hb/linear_beam.h"

#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "hb/internal/beam_mesh.h"
#include "tests/support/paper_setup.h"

namespace beamid::hb {
namespace {

using testing::Bisect;
using testing::kForcePosition_m;
using testing::PaperBeam;

constexpr double kRootTolerance = 1e-4;       // on λL, as the issue asks
constexpr double kModalSumTolerance = 1e-3;   // exact receptance vs truncated modal sum
constexpr double kExactTolerance = 1e-9;      // closed forms evaluated in double

// Physical-sign characteristic equation of the plain beam (docs/derivation.md),
// divided by cosh to stay finite: k(1/ch − c) + λ(s − c·th) = 0, k = k1/EI.
double Characteristic(double lambda_l, double k1_Nm_rad, const BeamProperties& beam) {
  const double l = beam.length_m;
  const double k = k1_Nm_rad / beam.BendingStiffness_Nm2();
  const double lambda = lambda_l / l;
  return k * (1.0 / std::cosh(lambda_l) - std::cos(lambda_l)) +
         lambda * (std::sin(lambda_l) - std::cos(lambda_l) * std::tanh(lambda_l));
}

double LambdaL(double omega, const BeamProperties& beam) {
  return beam.length_m * std::pow(beam.MassPerLength_kg_m() * omega * omega / beam.BendingStiffness_Nm2(), 0.25);
}

TEST(SegmentDynamicStiffness, StaticLimitIsTheTextbookBeamElement) {
  const double ei = 87.5, l = 0.23;
  const Eigen::Matrix4cd k = SegmentDynamicStiffness(0.0, ei, l);
  Eigen::Matrix4d expected;
  expected << 12, 6 * l, -12, 6 * l, 6 * l, 4 * l * l, -6 * l, 2 * l * l, -12, -6 * l, 12, -6 * l, 6 * l, 2 * l * l,
      -6 * l, 4 * l * l;
  expected *= ei / (l * l * l);
  EXPECT_LT((k.real() - expected).norm(), kExactTolerance * expected.norm());
  EXPECT_LT(k.imag().norm(), kExactTolerance * expected.norm());
}

TEST(SegmentDynamicStiffness, SeriesAndClosedFormsAgreeAtTheirSwitch) {
  // |μ|ℓ⁴ = 16 is where KrylovFunctions switches formulas; both sides must match.
  const double l = 0.3;
  const double mu_below = 15.999 / std::pow(l, 4), mu_above = 16.001 / std::pow(l, 4);
  const Eigen::Matrix4cd below = SegmentDynamicStiffness(mu_below, 87.5, l);
  const Eigen::Matrix4cd above = SegmentDynamicStiffness(mu_above, 87.5, l);
  EXPECT_LT((below - above).norm(), 1e-3 * below.norm());  // the 1.25e-4 step in μ itself
}

TEST(LinearBeam, FirstRootMatchesPinnedAndClampedLimits) {
  const BeamProperties beam = PaperBeam();
  LinearBeam pinned({.beam = beam, .support_stiffness_Nm_rad = 0.0}, kForcePosition_m);
  EXPECT_NEAR(LambdaL(pinned.NaturalFrequencies_rad_s(1)[0], beam), 3.92660, kRootTolerance);
  LinearBeam clamped({.beam = beam, .support_stiffness_Nm_rad = 1e12}, kForcePosition_m);
  EXPECT_NEAR(LambdaL(clamped.NaturalFrequencies_rad_s(1)[0], beam), 4.73004, kRootTolerance);
}

TEST(LinearBeam, NaturalFrequenciesSolveTheCharacteristicEquation) {
  const BeamProperties beam = PaperBeam();
  for (double k1 : {0.0, 10.0, 55.0, 300.0, 5000.0}) {
    LinearBeam linear({.beam = beam, .support_stiffness_Nm_rad = k1}, kForcePosition_m);
    const std::vector<double> omegas = linear.NaturalFrequencies_rad_s(5);
    for (int n = 0; n < 5; ++n) {
      // Mode n's root lies between the pinned and clamped roots of that mode.
      const double pinned = (n + 1.25) * std::numbers::pi;
      const double clamped = (n + 1.5) * std::numbers::pi;
      const double root = Bisect([&](double z) { return Characteristic(z, k1, beam); }, pinned - 0.01, clamped + 0.01);
      EXPECT_NEAR(LambdaL(omegas[n], beam), root, 1e-8) << "k1 = " << k1 << ", mode " << n + 1;
    }
  }
}

TEST(LinearBeam, StaticForceMatchesProppedCantileverClosedForm) {
  const BeamProperties beam = PaperBeam();
  LinearBeam linear({.beam = beam}, kForcePosition_m);
  const BeamDeflection static_shape = linear.RespondToForce(0.0);
  const double ei = beam.BendingStiffness_Nm2(), l = beam.length_m, a = kForcePosition_m;
  const double prop = a * a * (3 * l - a) / (2 * l * l * l);  // reaction at x = L per unit load
  for (double x : {0.05, 0.2, 0.4, 0.57, 0.59}) {
    const double load_part = x <= a ? x * x * (3 * a - x) / (6 * ei) : a * a * (3 * x - a) / (6 * ei);
    const double expected = load_part - prop * x * x * (3 * l - x) / (6 * ei);
    EXPECT_NEAR(static_shape.Displacement_m(x).real(), expected, kExactTolerance * 1e-2) << "x = " << x;
  }
}

TEST(LinearBeam, ReceptancesAreReciprocal) {
  // Maxwell–Betti: θ(L) per unit force at x_F equals y(x_F) per unit moment at L.
  LinearBeam linear({.beam = PaperBeam(), .support_stiffness_Nm_rad = 55.0, .support_damping_Nms_rad = 0.01},
                    kForcePosition_m);
  for (double omega : {0.0, 150.0, 340.0, 900.0, 2500.0}) {
    const Complex from_force = linear.RespondToForce(omega).SupportRotation_rad();
    const Complex from_moment = linear.RespondToSupportMoment(omega).Displacement_m(kForcePosition_m);
    EXPECT_LT(std::abs(from_force - from_moment), 1e-9 * std::abs(from_force)) << "omega = " << omega;
  }
}

TEST(LinearBeam, ExactReceptanceMatchesManyModeModalSum) {
  const BeamProperties beam = PaperBeam();
  LinearBeamModel model{.beam = beam, .support_stiffness_Nm_rad = 55.0};
  model.attachments.point_masses = {{0.100, 0.010}, {0.300, 0.010}, {0.570, 0.025}};
  LinearBeam linear(model, kForcePosition_m, {.max_frequency_hz = 40000.0});
  constexpr int kModes = 30;
  const std::vector<double> omegas = linear.NaturalFrequencies_rad_s(kModes);
  std::vector<BeamDeflection> shapes;
  std::vector<double> modal_masses;
  constexpr int kIntervals = 6000;  // Simpson's rule
  for (int n = 0; n < kModes; ++n) {
    shapes.push_back(linear.ModeShape(n));
    double integral = 0.0;
    for (int i = 0; i <= kIntervals; ++i) {
      const double weight = (i == 0 || i == kIntervals) ? 1.0 : (i % 2 ? 4.0 : 2.0);
      integral += weight * std::norm(shapes.back().Displacement_m(beam.length_m * i / kIntervals));
    }
    double mass = beam.MassPerLength_kg_m() * integral * beam.length_m / (3.0 * kIntervals);
    for (const auto& m : model.attachments.point_masses)
      mass += m.mass_kg * std::norm(shapes.back().Displacement_m(m.position_m));
    modal_masses.push_back(mass);
  }
  // Away from resonances: below the first, between the first and second.
  for (double omega : {0.5 * omegas[0], 0.8 * omegas[0], 1.3 * omegas[0], 0.5 * (omegas[0] + omegas[1])}) {
    const BeamDeflection exact = linear.RespondToForce(omega);
    for (double x : {0.1, 0.3, 0.45, 0.57}) {
      Complex modal = 0.0;
      for (int n = 0; n < kModes; ++n)
        modal += shapes[n].Displacement_m(x) * shapes[n].Displacement_m(kForcePosition_m) /
                 (modal_masses[n] * (omegas[n] * omegas[n] - omega * omega));
      EXPECT_LT(std::abs(exact.Displacement_m(x) - modal), kModalSumTolerance * std::abs(exact.Displacement_m(x)))
          << "x = " << x << ", omega = " << omega;
    }
  }
}

TEST(LinearBeam, CondensationReproducesTheFullSolution) {
  // Closing the condensed beam with the support spring must give the same θ
  // and the same sensor displacements as solving the whole beam.
  LinearBeamModel model{.beam = PaperBeam(), .support_stiffness_Nm_rad = 55.0, .support_damping_Nms_rad = 0.02};
  model.beam.loss_factor = 2e-3;
  model.attachments.clamp_rotational_stiffness_Nm_rad = 2e4;
  LinearBeam linear(model, kForcePosition_m);
  const std::vector<double> outputs = {0.1, 0.3, 0.57};
  for (double omega : {0.0, 340.0, 1020.0}) {
    const auto c = linear.CondenseOnSupportRotation(omega, outputs);
    const Complex support(model.support_stiffness_Nm_rad, omega * model.support_damping_Nms_rad);
    const Complex theta = c.blocked_moment_per_force_m / (c.rotational_stiffness_Nm_rad + support);
    const BeamDeflection full = linear.RespondToForce(omega);
    EXPECT_LT(std::abs(theta - full.SupportRotation_rad()), 1e-9 * std::abs(theta));
    for (std::size_t i = 0; i < outputs.size(); ++i) {
      const Complex y = c.displacement_per_force_m_N[i] + c.displacement_per_rotation_m[i] * theta;
      EXPECT_LT(std::abs(y - full.Displacement_m(outputs[i])), 1e-9 * std::abs(y));
    }
  }
}

TEST(LinearBeam, RejectsNonPhysicalInput) {
  BeamProperties beam = PaperBeam();
  beam.thickness_m = -1.0;
  EXPECT_THROW(LinearBeam({.beam = beam}, 0.57), std::invalid_argument);
  EXPECT_THROW(LinearBeam({.beam = PaperBeam()}, 0.75), std::invalid_argument);
  EXPECT_THROW(LinearBeam({.beam = PaperBeam(), .support_stiffness_Nm_rad = -3.0}, 0.57), std::invalid_argument);
}

}  // namespace
}  // namespace beamid::hb
