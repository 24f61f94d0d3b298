// The closed-form plain beam against literature roots, hand-derived static
// solutions, energy identities, and the independent segmented
// dynamic-stiffness LinearBeam.
#include "hb/closed_form_beam.h"

#include <cmath>
#include <cstdio>
#include <string>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>

#include "hb/linear_beam.h"
#include "tests/support/paper_setup.h"

namespace beamid::hb {
namespace {

// Root tolerance of the issue (4–5 significant digits of published tables).
constexpr double kTableTolerance = 1e-4;
// Two exact formulations in double precision.
constexpr double kExactRelative = 1e-8;

const std::vector<double> kSupportStiffnesses_Nm_rad = {0.0, 150.0, 1.0e3, 1.0e5};

// Relative difference |a − b| / scale.
double Relative(double a, double b, double scale) { return std::abs(a - b) / scale; }

TEST(CharacteristicRootsTest, PinnedAndClampedLimitsMatchTables) {
  // Clamped–pinned (tan β = tanh β) and clamped–clamped (cos β·cosh β = 1)
  // eigenvalues from the standard tables (Blevins, Formulas for natural
  // frequency and mode shape, Table 8-1).
  const std::vector<double> pinned = {3.92660, 7.06858, 10.21018, 13.35177, 16.49336};
  const std::vector<double> clamped = {4.73004, 7.85320, 10.99561, 14.13717, 17.27876};
  const std::vector<double> roots_pinned = CharacteristicRoots(0.0, 5);
  const std::vector<double> roots_infinite = CharacteristicRoots(std::numeric_limits<double>::infinity(), 5);
  const std::vector<double> roots_stiff = CharacteristicRoots(1e9, 5);
  for (int n = 0; n < 5; ++n) {
    EXPECT_NEAR(roots_pinned[n], pinned[n], kTableTolerance) << "mode " << n + 1;
    EXPECT_NEAR(roots_infinite[n], clamped[n], kTableTolerance) << "mode " << n + 1;
    EXPECT_NEAR(roots_stiff[n], clamped[n], kTableTolerance) << "k1·L = 1e9, mode " << n + 1;
    // The defining transcendental equations hold at the computed roots.
    EXPECT_NEAR(std::tan(roots_pinned[n]), std::tanh(roots_pinned[n]), 1e-12);
    EXPECT_NEAR(std::cos(roots_infinite[n]), 1.0 / std::cosh(roots_infinite[n]), 1e-14);
  }
}

TEST(CharacteristicRootsTest, RootsRiseMonotonicallyBetweenThePinnedAndClampedRoots) {
  const std::vector<double> pinned = CharacteristicRoots(0.0, 6);
  const std::vector<double> clamped = CharacteristicRoots(std::numeric_limits<double>::infinity(), 6);
  std::vector<double> previous = pinned;
  for (double stiffness_l : {1e-3, 0.1, 1.0, 10.0, 100.0, 1e4}) {
    const std::vector<double> roots = CharacteristicRoots(stiffness_l, 6);
    for (int n = 0; n < 6; ++n) {
      EXPECT_GT(roots[n], previous[n]) << "k1·L = " << stiffness_l << ", mode " << n + 1;
      EXPECT_LT(roots[n], clamped[n]);
      // The unscaled characteristic equation of the physical sign
      // k1(1 − cos·cosh) + λ(sin·cosh − cos·sinh) = 0, divided by cosh.
      EXPECT_NEAR(CharacteristicFunction(roots[n], stiffness_l), 0.0, 1e-10 * (1.0 + stiffness_l));
    }
    previous = roots;
  }
}

TEST(CharacteristicRootsTest, RejectsNegativeStiffnessAndZeroCount) {
  EXPECT_THROW(CharacteristicRoots(-1.0, 3), std::invalid_argument);
  EXPECT_THROW(CharacteristicRoots(std::numeric_limits<double>::quiet_NaN(), 3), std::invalid_argument);
  EXPECT_THROW(CharacteristicRoots(1.0, 0), std::invalid_argument);
  EXPECT_THROW(ClosedFormBeam(testing::PaperBeam(), -5.0), std::invalid_argument);
  const ClosedFormBeam beam(testing::PaperBeam(), 10.0);
  EXPECT_THROW(beam.PointForceShape(100.0, 0.7), std::invalid_argument);
  EXPECT_THROW(beam.EndMomentShape(-1.0), std::invalid_argument);
}

TEST(ClosedFormBeamTest, NaturalFrequenciesMatchWittrickWilliamsLinearBeam) {
  for (double k1 : kSupportStiffnesses_Nm_rad) {
    const ClosedFormBeam closed(testing::PaperBeam(), k1);
    const LinearBeam exact(LinearBeamModel{testing::PaperBeam(), {}, k1, 0.0}, testing::kForcePosition_m);
    const std::vector<double> ours = closed.NaturalFrequencies_rad_s(6);
    const std::vector<double> theirs = exact.NaturalFrequencies_rad_s(6);
    for (int n = 0; n < 6; ++n)
      EXPECT_LT(Relative(ours[n], theirs[n], theirs[n]), kExactRelative) << "K1 = " << k1 << ", mode " << n + 1;
  }
}

TEST(ClosedFormBeamTest, ModeShapesMatchLinearBeam) {
  // Shapes are compared after a least-squares scale: LinearBeam finds max|w|
  // on 601 samples, which leaves its scale off by up to ~1e-4 for mode 5
  // (the sampled peak is below the true one); that scale is checked apart.
  const double length = testing::PaperBeam().length_m;
  for (double k1 : kSupportStiffnesses_Nm_rad) {
    const ClosedFormBeam closed(testing::PaperBeam(), k1);
    const LinearBeam exact(LinearBeamModel{testing::PaperBeam(), {}, k1, 0.0}, testing::kForcePosition_m);
    for (int mode = 0; mode < 5; ++mode) {
      const ClosedFormShape ours = closed.ModeShape(mode);
      const BeamDeflection theirs = exact.ModeShape(mode);
      std::vector<double> a, b, a1, b1;
      for (int i = 0; i <= 48; ++i) {
        const double x = length * i / 48;
        a.push_back(ours.Value(x));
        b.push_back(theirs.Displacement_m(x).real());
        a1.push_back(ours.Value(x, 1));
        b1.push_back(theirs.Slope_rad(x).real());
        EXPECT_LE(std::abs(a.back()), 1.0 + 1e-12);
        EXPECT_NEAR(theirs.Displacement_m(x).imag(), 0.0, 1e-12);
      }
      double ab = 0.0, bb = 0.0;
      for (std::size_t i = 0; i < a.size(); ++i) {
        ab += a[i] * b[i];
        bb += b[i] * b[i];
      }
      const double scale = ab / bb;
      EXPECT_NEAR(scale, 1.0, 2e-4) << "K1 " << k1 << " mode " << mode;
      const double slope_scale = closed.Wavenumber_per_m(closed.NaturalFrequencies_rad_s(mode + 1).back());
      for (std::size_t i = 0; i < a.size(); ++i) {
        EXPECT_NEAR(a[i], scale * b[i], 1e-8) << "K1 " << k1 << " mode " << mode << " sample " << i;
        EXPECT_NEAR(a1[i], scale * b1[i], 1e-8 * slope_scale) << "K1 " << k1 << " mode " << mode << " sample " << i;
      }
    }
  }
}

TEST(ClosedFormBeamTest, ModeShapesSatisfyRayleighQuotientAndMassOrthogonalityResidue) {
  // ω² = (EI·∫w''² + K1·w'(L)²)/(ρA·∫w²): energy identity, independent of how
  // the root was found; checks the derivatives and the quadrature.
  const BeamProperties beam = testing::PaperBeam();
  const double ei = beam.BendingStiffness_Nm2(), rho_a = beam.MassPerLength_kg_m(), length = beam.length_m;
  for (double k1 : kSupportStiffnesses_Nm_rad) {
    const ClosedFormBeam closed(beam, k1);
    const std::vector<double> omegas = closed.NaturalFrequencies_rad_s(5);
    for (int mode = 0; mode < 5; ++mode) {
      const ClosedFormShape w = closed.ModeShape(mode);
      const double slope = w.Value(length, 1);
      const double rayleigh = (ei * w.SquareIntegral(2) + k1 * slope * slope) / (rho_a * w.SquareIntegral(0));
      EXPECT_LT(Relative(rayleigh, omegas[mode] * omegas[mode], omegas[mode] * omegas[mode]), 1e-10);
      // Beam equation w'''' = μ⁴·w at an interior point.
      const double mu = closed.Wavenumber_per_m(omegas[mode]);
      EXPECT_NEAR(w.Value(0.37, 4), std::pow(mu, 4) * w.Value(0.37), 1e-9 * std::pow(mu, 4));
    }
    // Residue of the end-moment receptance at ω1 is w'(L)²/m_eff.
    const ClosedFormShape w = closed.ModeShape(0);
    const double slope = w.Value(length, 1);
    const double omega1 = omegas[0];
    double residue = 0.0;
    for (double side : {-1.0, 1.0}) {
      const double omega = omega1 * (1.0 + side * 1e-6);
      residue += 0.5 * (omega1 * omega1 - omega * omega) * closed.RotationPerEndMoment_rad_Nm(omega);
    }
    EXPECT_LT(Relative(residue, slope * slope / (rho_a * w.SquareIntegral(0)), residue), 1e-6) << "K1 " << k1;
  }
}

TEST(ClosedFormBeamTest, StaticEndMomentShapeIsTheHandDerivedCubic) {
  // P'''' = 0, P(0) = P'(0) = P(L) = 0, P''(L) + k1·P'(L) = 1
  //   ⇒ P = (x³ − L·x²)/(L·(4 + k1·L)).
  const BeamProperties beam = testing::PaperBeam();
  const double length = beam.length_m;
  for (double k1 : kSupportStiffnesses_Nm_rad) {
    const ClosedFormBeam closed(beam, k1);
    const double k1_per_m = k1 / beam.BendingStiffness_Nm2();
    const double scale = 1.0 / (length * (4.0 + k1_per_m * length));
    const ClosedFormShape p = closed.EndMomentShape(0.0);
    const ClosedFormShape almost_static = closed.EndMomentShape(1e-3);  // series path
    for (int i = 0; i <= 10; ++i) {
      const double x = length * i / 10;
      const double expected = (x * x * x - length * x * x) * scale;
      EXPECT_NEAR(p.Value(x), expected, 1e-14);
      EXPECT_NEAR(p.Value(x, 1), (3.0 * x * x - 2.0 * length * x) * scale, 1e-13);
      EXPECT_NEAR(almost_static.Value(x), expected, 1e-12);
    }
  }
}

TEST(ClosedFormBeamTest, EndMomentShapeEqualsBendingStiffnessTimesLinearBeamMomentReceptance) {
  // Q(x, μ) of the seed (our P) built from its 2×2 boundary system must equal
  // EI × the receptance of the segmented dynamic-stiffness model, at the
  // frequencies the multiple-scales model uses (0, Ω, 2Ω, 3Ω) and above.
  const BeamProperties beam = testing::PaperBeam();
  const double ei = beam.BendingStiffness_Nm2(), length = beam.length_m;
  for (double k1 : kSupportStiffnesses_Nm_rad) {
    const ClosedFormBeam closed(beam, k1);
    const LinearBeam exact(LinearBeamModel{beam, {}, k1, 0.0}, testing::kForcePosition_m);
    const double omega1 = closed.NaturalFrequencies_rad_s(1)[0];
    for (double ratio : {0.0, 0.5, 0.999, 1.3, 2.0, 3.0, 7.7}) {
      const double omega = ratio * omega1;
      const ClosedFormShape p = closed.EndMomentShape(omega);
      const BeamDeflection theirs = exact.RespondToSupportMoment(omega);
      double scale = 0.0;
      for (int i = 0; i <= 20; ++i) scale = std::max(scale, std::abs(theirs.Displacement_m(length * i / 20)));
      for (int i = 0; i <= 20; ++i) {
        const double x = length * i / 20;
        EXPECT_LT(std::abs(p.Value(x) / ei - theirs.Displacement_m(x)), kExactRelative * scale)
            << "K1 " << k1 << " Ω/ω1 " << ratio << " x " << x;
      }
      EXPECT_LT(std::abs(closed.RotationPerEndMoment_rad_Nm(omega) - theirs.SupportRotation_rad()),
                kExactRelative * std::abs(theirs.SupportRotation_rad()));
    }
  }
}

TEST(ClosedFormBeamTest, PointForceShapeMatchesLinearBeamAndIsReciprocal) {
  const BeamProperties beam = testing::PaperBeam();
  const double ei = beam.BendingStiffness_Nm2(), length = beam.length_m;
  const double k1 = 150.0;
  const ClosedFormBeam closed(beam, k1);
  const double omega1 = closed.NaturalFrequencies_rad_s(1)[0];
  for (double force_position : {0.2, testing::kForcePosition_m}) {
    const LinearBeam exact(LinearBeamModel{beam, {}, k1, 0.0}, force_position);
    for (double ratio : {0.0, 0.8, 1.01, 2.5}) {
      const double omega = ratio * omega1;
      const ClosedFormShape g = closed.PointForceShape(omega, force_position);
      const BeamDeflection theirs = exact.RespondToForce(omega);
      const double scale = std::abs(theirs.Displacement_m(force_position));
      for (int i = 0; i <= 30; ++i) {
        const double x = length * i / 30;
        EXPECT_LT(std::abs(g.Value(x) / ei - theirs.Displacement_m(x)), kExactRelative * scale)
            << "x_F " << force_position << " Ω/ω1 " << ratio << " x " << x;
      }
    }
  }
  // Maxwell–Betti: the displacement at a due to a force at b equals the
  // displacement at b due to a force at a.
  for (double omega : {0.0, 0.9 * omega1, 4.0 * omega1}) {
    const double a = 0.13, b = 0.52;
    EXPECT_NEAR(closed.PointForceShape(omega, b).Value(a), closed.PointForceShape(omega, a).Value(b),
                1e-12 * std::abs(closed.PointForceShape(omega, b).Value(a)));
  }
}

TEST(ClosedFormBeamTest, SupportStiffnessForA54HzFirstResonance) {
  // The model file example (docs/model-file.md): the K1 that puts the first resonance of the paper's
  // beam at 54.0 Hz, found on the closed form and confirmed on LinearBeam.
  const BeamProperties beam = testing::PaperBeam();
  const double target_rad_s = 2.0 * std::numbers::pi * 54.0;
  const double k1 = testing::Bisect(
      [&](double k) { return ClosedFormBeam(beam, k).NaturalFrequencies_rad_s(1)[0] - target_rad_s; }, 0.0, 1e4);
  const LinearBeam exact(LinearBeamModel{beam, {}, k1, 0.0}, testing::kForcePosition_m);
  EXPECT_LT(Relative(exact.NaturalFrequencies_rad_s(1)[0], target_rad_s, target_rad_s), kExactRelative);
  const double lambda_l = CharacteristicRoots(k1 * beam.length_m / beam.BendingStiffness_Nm2(), 1)[0];
  EXPECT_GT(lambda_l, 3.92660);  // between pinned and clamped
  EXPECT_LT(lambda_l, 4.73004);
  ::testing::Test::RecordProperty("k1_for_54Hz_Nm_rad", std::to_string(k1));
  std::printf("K1 for a 54.0 Hz first resonance: %.4f N*m/rad (lambda1*L = %.5f)\n", k1, lambda_l);
}

TEST(ClosedFormBeamTest, StaysAccurateAtHighWavenumber) {
  // μL ≈ 30: the exponential representation neither overflows nor cancels.
  const BeamProperties beam = testing::PaperBeam();
  const ClosedFormBeam closed(beam, 1.0e3);
  const LinearBeam exact(LinearBeamModel{beam, {}, 1.0e3, 0.0}, testing::kForcePosition_m);
  const double mu = 30.0 / beam.length_m;
  const double omega = mu * mu * std::sqrt(beam.BendingStiffness_Nm2() / beam.MassPerLength_kg_m());
  const ClosedFormShape p = closed.EndMomentShape(omega);
  const BeamDeflection theirs = exact.RespondToSupportMoment(omega);
  const double scale = std::abs(theirs.SupportRotation_rad());
  for (double x : {0.05, 0.3, 0.55, 0.59})
    EXPECT_LT(std::abs(p.Value(x) / beam.BendingStiffness_Nm2() - theirs.Displacement_m(x)), 1e-7 * scale);
  EXPECT_NEAR(p.Value(beam.length_m, 2) + 1.0e3 / beam.BendingStiffness_Nm2() * p.Value(beam.length_m, 1), 1.0,
              1e-9);
}

}  // namespace
}  // namespace beamid::hb
