// The finite-element beam against exact solutions: the characteristic
// equation of the clamped beam with a rotational spring at a pinned end, and
// the exact dynamic-stiffness beam (hb/linear_beam.h) with attachments.
#include "hb/fe_beam.h"

#include <cmath>
#include <functional>
#include <numbers>
#include <vector>

#include <gtest/gtest.h>

#include "hb/linear_beam.h"

namespace beamid::hb {
namespace {

constexpr double kFrequencyTolerance = 5e-4;  // 0.05 %

BeamProperties PaperBeam() { return BeamProperties{}; }

// Roots λL of k(1 − cos λL cosh λL) + λ(sin λL cosh λL − cos λL sinh λL) = 0,
// k = k1/EI, scaled by e^{−λL} to stay finite; returned as ω = (λ²)·sqrt(EI/ρA).
std::vector<double> ExactFrequencies_rad_s(const BeamProperties& beam, double k1_Nm_rad, int count) {
  const double length = beam.length_m;
  const double k = k1_Nm_rad / beam.BendingStiffness_Nm2();
  auto characteristic = [&](double lambda_l) {
    const double lambda = lambda_l / length;
    const double c = std::cos(lambda_l), s = std::sin(lambda_l);
    const double ch = 0.5 * (1.0 + std::exp(-2.0 * lambda_l)), sh = 0.5 * (1.0 - std::exp(-2.0 * lambda_l));
    return k * (std::exp(-lambda_l) - c * ch) + lambda * (s * ch - c * sh);
  };
  std::vector<double> omegas;
  double previous = characteristic(0.5);
  for (double x = 0.5; omegas.size() < static_cast<size_t>(count); x += 1e-3) {
    const double current = characteristic(x + 1e-3);
    if ((previous < 0) != (current < 0)) {
      double lo = x, hi = x + 1e-3;
      for (int i = 0; i < 100; ++i) {
        const double mid = 0.5 * (lo + hi);
        ((characteristic(mid) < 0) == (characteristic(lo) < 0) ? lo : hi) = mid;
      }
      const double lambda = 0.5 * (lo + hi) / length;
      omegas.push_back(lambda * lambda * std::sqrt(beam.BendingStiffness_Nm2() / beam.MassPerLength_kg_m()));
    }
    previous = current;
  }
  return omegas;
}

void ExpectFirstThreeAgree(const std::vector<double>& fe, const std::vector<double>& exact) {
  ASSERT_GE(fe.size(), 3u);
  ASSERT_GE(exact.size(), 3u);
  for (int i = 0; i < 3; ++i)
    EXPECT_NEAR(fe[i] / exact[i], 1.0, kFrequencyTolerance) << "mode " << i + 1 << ": FE " << fe[i] / (2 * std::numbers::pi)
                                                          << " Hz, exact " << exact[i] / (2 * std::numbers::pi) << " Hz";
}

const std::vector<double> kPaperNodes{0.100, 0.300, 0.570};

TEST(FeBeamTest, NaturalFrequenciesMatchCharacteristicEquationOverSupportStiffness) {
  const FeBeam fe(PaperBeam(), LinearAttachments{}, kPaperNodes);
  for (double k1 : {0.0, 150.0, 500.0, 1e5}) {
    SCOPED_TRACE(k1);
    ExpectFirstThreeAgree(fe.NaturalFrequencies_rad_s(3, k1), ExactFrequencies_rad_s(PaperBeam(), k1, 3));
  }
}

TEST(FeBeamTest, PaperSupportGivesFirstResonanceNear54Hz) {
  // The examples' k1 = 150 N·m/rad puts the first resonance at the paper's
  // ~54 Hz (the pinned end alone gives 50.9 Hz).
  const double f1_hz = ExactFrequencies_rad_s(PaperBeam(), 150.0, 1)[0] / (2 * std::numbers::pi);
  EXPECT_NEAR(f1_hz, 54.0, 0.1);
  EXPECT_NEAR(ExactFrequencies_rad_s(PaperBeam(), 0.0, 1)[0] / (2 * std::numbers::pi), 50.9, 0.1);
}

TEST(FeBeamTest, CoarseMeshStillWithinTolerance) {
  // Only the required nodes plus a 10-element floor.
  const FeBeam fe(PaperBeam(), LinearAttachments{}, kPaperNodes, FeBeamOptions{.min_elements = 10});
  ExpectFirstThreeAgree(fe.NaturalFrequencies_rad_s(3, 150.0), ExactFrequencies_rad_s(PaperBeam(), 150.0, 3));
}

TEST(FeBeamTest, AttachmentsMatchExactDynamicStiffnessBeam) {
  LinearAttachments attachments;
  attachments.clamp_rotational_stiffness_Nm_rad = 2.0e4;
  attachments.support_translational_stiffness_N_m = 5.0e5;
  attachments.point_masses = {{0.570, 0.030}, {0.300, 0.010}};
  const FeBeam fe(PaperBeam(), attachments, kPaperNodes);
  const LinearBeam exact(LinearBeamModel{.beam = PaperBeam(), .attachments = attachments, .support_stiffness_Nm_rad = 150.0},
                         0.570);
  ExpectFirstThreeAgree(fe.NaturalFrequencies_rad_s(3, 150.0), exact.NaturalFrequencies_rad_s(3));
}

TEST(FeBeamTest, RequestedPositionsAreNodesAndConstraintsHold) {
  const FeBeam fe(PaperBeam(), LinearAttachments{}, kPaperNodes);
  for (double x : kPaperNodes) EXPECT_NE(fe.DeflectionDof(x), FeBeam::kConstrained);
  EXPECT_EQ(fe.DeflectionDof(0.0), FeBeam::kConstrained);
  EXPECT_EQ(fe.DeflectionDof(0.6), FeBeam::kConstrained);
  EXPECT_THROW(fe.DeflectionDof(0.1234567), std::invalid_argument);
  EXPECT_THROW(FeBeam(PaperBeam(), LinearAttachments{}, std::vector<double>{0.7}), std::invalid_argument);
  // Ideal clamp and support: 2 DOFs per node minus y(0), y'(0), y(L).
  EXPECT_EQ(fe.NumDofs(), 2 * (fe.NumElements() + 1) - 3);
}

}  // namespace
}  // namespace beamid::hb
