// The multiple-scales model against independent references: the exact linear
// receptance of LinearBeam (linear limit), the Duffing backbone built from
// LinearBeam's own receptance residue, the harmonic algebra redone by
// sampling the support moment over a period, and the Duffing peak.
#include "hb/multiple_scales.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>

#include "hb/linear_beam.h"
#include "tests/support/paper_setup.h"

namespace beamid::hb {
namespace {

constexpr double kSupportStiffness_Nm_rad = 150.0;  // first resonance ≈ 54 Hz
constexpr double kLinearLimitTolerance = 0.005;     // required: first harmonic within 0.5 %
constexpr double kExactRelative = 1e-8;

PolynomialSupportLaw::Coefficients Support(double k2, double k3, double c) {
  return {.k1_Nm_rad = kSupportStiffness_Nm_rad, .k2_Nm_rad2 = k2, .k3_Nm_rad3 = k3, .c_Nms_rad = c};
}

LinearBeam Exact(double c) {
  return LinearBeam(LinearBeamModel{testing::PaperBeam(), {}, kSupportStiffness_Nm_rad, c}, testing::kForcePosition_m);
}

// Harmonic k phasor of N equispaced samples over one period (k = 0: mean),
// docs/fourier-convention.md.
Complex Harmonic(const std::vector<double>& samples, int k) {
  const int n = static_cast<int>(samples.size());
  Complex sum = 0.0;
  for (int i = 0; i < n; ++i) sum += samples[i] * std::polar(1.0, -2.0 * std::numbers::pi * k * i / n);
  return sum * (k == 0 ? 1.0 : 2.0) / static_cast<double>(n);
}

TEST(MultipleScalesTest, LinearLimitEqualsExactReceptanceAcrossASweep) {
  // K2 = K3 = 0: the generalised model keeps the damper exact, so its first
  // harmonic must equal the damped receptance of LinearBeam (another
  // formulation) at every Ω and C, far inside the 0.5 %. The seed's
  // form is only first-order in C and Ω − ω0: 0.5 % holds for it near ω0
  // with light damping.
  for (double c : {0.002, 0.05, 0.2}) {
    const MultipleScalesModel model(testing::PaperBeam(), Support(0.0, 0.0, c), testing::kForcePosition_m);
    const MultipleScalesModel seed(testing::PaperBeam(), Support(0.0, 0.0, c), testing::kForcePosition_m,
                                   {.harmonic_frequency = MultipleScalesHarmonicFrequency::kNatural});
    const LinearBeam exact = Exact(c);
    const double omega0 = model.NaturalFrequency_rad_s();
    double worst = 0.0, worst_seed = 0.0;
    for (int i = 0; i <= 40; ++i) {
      const double omega = omega0 * (0.5 + i / 40.0);
      const std::vector<Complex> solutions = model.Solve(omega, 1.0);
      ASSERT_EQ(solutions.size(), 1u);
      const BeamDeflection reference = exact.RespondToForce(omega);
      for (double x : testing::kSensorPositions_m) {
        const MultipleScalesModel::Harmonics h = model.Response(x, solutions[0], omega, 1.0);
        const Complex expected = reference.Displacement_m(x);
        const double error = std::abs(h.h1_m - expected) / std::abs(expected);
        worst = std::max(worst, error);
        const Complex rotation = reference.SupportRotation_rad();
        EXPECT_LT(std::abs(model.FirstHarmonicRotation_rad(solutions[0], omega, 1.0) - rotation),
                  1e-9 * std::abs(rotation));
        EXPECT_LT(error, 1e-9) << "c " << c << " Ω/ω0 " << omega / omega0 << " x " << x;
        EXPECT_LT(error, kLinearLimitTolerance);
        EXPECT_EQ(h.h0_m, 0.0);
        EXPECT_EQ(std::abs(h.h2_m), 0.0);
        EXPECT_EQ(std::abs(h.h3_m), 0.0);
        if (std::abs(omega / omega0 - 1.0) <= 0.0125 && c <= 0.002) {
          const Complex u = seed.Solve(omega, 1.0).front();
          const double seed_error = std::abs(seed.Response(x, u, omega, 1.0).h1_m - expected) / std::abs(expected);
          worst_seed = std::max(worst_seed, seed_error);
          EXPECT_LT(seed_error, kLinearLimitTolerance) << "seed form, Ω/ω0 " << omega / omega0 << " x " << x;
        }
      }
    }
    std::printf("linear limit, c = %.3g N*m*s/rad: worst first-harmonic error %.2e over 0.5..1.5 w0", c, worst);
    if (c <= 0.002) std::printf("; seed form %.2e over 0.9875..1.0125 w0", worst_seed);
    std::printf("\n");
  }
}

TEST(MultipleScalesTest, DuffingBackboneOfTheSingleModeFromIndependentModalData) {
  // K2 = 0: Ω² = ω0² + ¾·K3·w'(L)⁴·a²/m_eff. The modal data come from
  // LinearBeam: ω0 from Wittrick–Williams, w'(L)²/m_eff from the residue of
  // its end-moment receptance at ω0 (normalisation-free), θ = a·w'(L).
  const double k3 = 2.0e4;
  const MultipleScalesModel model(testing::PaperBeam(), Support(0.0, k3, 0.0), testing::kForcePosition_m);
  const LinearBeam exact = Exact(0.0);
  const double omega0 = exact.NaturalFrequencies_rad_s(1)[0];
  EXPECT_LT(std::abs(model.NaturalFrequency_rad_s() - omega0), kExactRelative * omega0);
  double residue = 0.0;  // w'(L)²/m_eff
  for (double side : {-1.0, 1.0}) {
    const double omega = omega0 * (1.0 + side * 1e-6);
    residue += 0.5 * (omega0 * omega0 - omega * omega) * exact.RespondToSupportMoment(omega).SupportRotation_rad().real();
  }
  double previous = omega0;
  for (double a : {1e-4, 5e-4, 1e-3, 2e-3, 4e-3}) {
    const double theta = a * model.SupportSlope_per_m();
    const double expected = std::sqrt(omega0 * omega0 + 0.75 * k3 * residue * theta * theta);
    const double backbone = model.Backbone_rad_s(a);
    EXPECT_LT(std::abs(backbone - expected), 1e-6 * omega0) << "a = " << a;
    EXPECT_GT(backbone, previous) << "K3 > 0 must harden";
    previous = backbone;
  }
}

TEST(MultipleScalesTest, QuadraticStiffnessAloneSoftens) {
  // Γ = 2·K2²·(2·G(0) + G(2Ω))·w'⁴ > 0 when the static and second-harmonic
  // end compliances add up positive (checked here on LinearBeam).
  const MultipleScalesModel model(testing::PaperBeam(), Support(200.0, 0.0, 0.0), testing::kForcePosition_m);
  const LinearBeam exact = Exact(0.0);
  const double omega0 = model.NaturalFrequency_rad_s();
  const double g0 = exact.RespondToSupportMoment(0.0).SupportRotation_rad().real();
  const double g2 = exact.RespondToSupportMoment(2.0 * omega0).SupportRotation_rad().real();
  ASSERT_GT(2.0 * g0 + g2, 0.0);
  double previous = omega0;
  for (double a : {1e-4, 1e-3, 3e-3}) {
    const double backbone = model.Backbone_rad_s(a);
    EXPECT_LT(backbone, previous) << "a = " << a;
    previous = backbone;
  }
}

TEST(MultipleScalesTest, HarmonicAlgebraMatchesASampledPeriodAndLinearBeamReceptances) {
  // Redo the cascade numerically: θ(t) = θa(t) + θb(t) with θb the static and
  // second-harmonic rotations produced by the moment K2·θa², then sample
  // M(t) = K2·(θa² + 2·θa·θb) + K3·θa³ (the terms of order ≤ ε²; C = 0 here,
  // the damper is checked by the linear limit and against harmonic balance)
  // and take its harmonics. With θa = θ0 = U·w'(L) the first harmonic is M1;
  // with θa = θ1 (the whole first-harmonic rotation) harmonic k of M drives
  // the displacement harmonic −M_k·G_xM(x, kΩ).
  const double k2 = 300.0, k3 = -2.0e4, c = 0.0;
  const MultipleScalesModel model(testing::PaperBeam(), Support(k2, k3, c), testing::kForcePosition_m);
  const LinearBeam exact = Exact(0.0);
  const double omega = 1.01 * model.NaturalFrequency_rad_s();
  const Complex u = std::polar(2e-3, 0.7);
  const BeamDeflection static_moment = exact.RespondToSupportMoment(0.0);
  const BeamDeflection second_moment = exact.RespondToSupportMoment(2.0 * omega);
  const BeamDeflection third_moment = exact.RespondToSupportMoment(3.0 * omega);
  auto sampled_moment = [&](Complex theta_a) {
    const double theta_static = -(k2 * std::norm(theta_a) / 2.0) * static_moment.SupportRotation_rad().real();
    const Complex theta2 = -(k2 * theta_a * theta_a / 2.0) * second_moment.SupportRotation_rad();
    constexpr int kSamples = 64;
    std::vector<double> moment(kSamples);
    for (int i = 0; i < kSamples; ++i) {
      const Complex phase = std::polar(1.0, 2.0 * std::numbers::pi * i / kSamples);
      const double tha = (theta_a * phase).real();
      const double thb = theta_static + (theta2 * phase * phase).real();
      moment[i] = k2 * (tha * tha + 2.0 * tha * thb) + k3 * tha * tha * tha;
    }
    return moment;
  };
  const Complex m1 = Harmonic(sampled_moment(u * model.SupportSlope_per_m()), 1);
  EXPECT_LT(std::abs(model.SupportMomentFirstHarmonic_Nm(u, omega, 1.0) - m1), 1e-10 * std::abs(m1));
  const std::vector<double> moment = sampled_moment(model.FirstHarmonicRotation_rad(u, omega, 1.0));
  for (double x : testing::kSensorPositions_m) {
    const MultipleScalesModel::Harmonics h = model.Response(x, u, omega, 1.0);
    const Complex h0 = -Harmonic(moment, 0) * static_moment.Displacement_m(x);
    const Complex h2 = -Harmonic(moment, 2) * second_moment.Displacement_m(x);
    const Complex h3 = -Harmonic(moment, 3) * third_moment.Displacement_m(x);
    EXPECT_LT(std::abs(h.h0_m - h0), kExactRelative * std::abs(h0)) << "x " << x;
    EXPECT_LT(std::abs(h.h2_m - h2), kExactRelative * std::abs(h2)) << "x " << x;
    EXPECT_LT(std::abs(h.h3_m - h3), kExactRelative * std::abs(h3)) << "x " << x;
  }
}

TEST(MultipleScalesTest, AmplitudeFrequencyRootsSatisfyTheSolvabilityCondition) {
  // Solve() uses the cubic in a² with Γ; the residual rebuilds M1 from the
  // harmonic rotations: two formulations of the same condition.
  for (auto frequency : {MultipleScalesHarmonicFrequency::kExcitation, MultipleScalesHarmonicFrequency::kNatural}) {
    const MultipleScalesModel model(testing::PaperBeam(), Support(100.0, 1.0e5, 0.02), testing::kForcePosition_m,
                                    {.harmonic_frequency = frequency});
    const double omega0 = model.NaturalFrequency_rad_s();
    const Complex force = std::polar(4.0, -0.4);
    const double scale = std::abs(force * model.ModeShape(testing::kForcePosition_m));
    int multiple = 0;
    for (int i = 0; i <= 60; ++i) {
      const double omega = omega0 * (0.97 + 0.08 * i / 60.0);
      const std::vector<Complex> solutions = model.Solve(omega, force);
      ASSERT_TRUE(solutions.size() == 1 || solutions.size() == 3) << solutions.size();
      if (solutions.size() == 3) ++multiple;
      for (Complex u : solutions)
        EXPECT_LT(std::abs(model.SolvabilityResidual_N(u, omega, force)), 1e-10 * scale) << "Ω/ω0 " << omega / omega0;
    }
    EXPECT_GT(multiple, 0) << "the sweep should cross the fold";
  }
}

TEST(MultipleScalesTest, BothBranchesExistPastTheFoldAndPeakOnTheBackbone) {
  // Duffing peak of the seed's form: where the upper branch ends the
  // restoring terms cancel (Ω on the backbone) and a = |F1·w(x_F)|/(ω0·C·w'(L)²).
  const double c = 0.02, force = 4.0;
  const MultipleScalesModel model(testing::PaperBeam(), Support(0.0, 1.0e5, c), testing::kForcePosition_m,
                                  {.harmonic_frequency = MultipleScalesHarmonicFrequency::kNatural});
  const double omega0 = model.NaturalFrequency_rad_s();
  const double slope2 = model.SupportSlope_per_m() * model.SupportSlope_per_m();
  const double peak = std::abs(force * model.ModeShape(testing::kForcePosition_m)) / (omega0 * c * slope2);
  const double peak_omega = model.Backbone_rad_s(peak);
  ASSERT_GT(peak_omega, 1.005 * omega0) << "the test needs a clear fold";

  std::vector<double> omegas;
  for (int i = 0; i <= 4000; ++i) omegas.push_back(omega0 * (0.98 + (peak_omega / omega0 - 0.98 + 0.01) * i / 4000.0));
  const std::vector<MultipleScalesModel::SweepPoint> sweep = model.Sweep(omegas, force);
  double largest = 0.0, largest_omega = 0.0;
  int first_triple = -1, last_triple = -1;
  for (std::size_t i = 0; i < sweep.size(); ++i) {
    const auto& point = sweep[i];
    ASSERT_TRUE(point.modal_phasors_m.size() == 1 || point.modal_phasors_m.size() == 3);
    if (point.modal_phasors_m.size() == 3) {
      if (first_triple < 0) first_triple = static_cast<int>(i);
      last_triple = static_cast<int>(i);
      // Lower, middle (unstable) and upper branch.
      EXPECT_LE(std::abs(point.modal_phasors_m[0]), std::abs(point.modal_phasors_m[1]));
      EXPECT_LE(std::abs(point.modal_phasors_m[1]), std::abs(point.modal_phasors_m[2]));
    }
    if (std::abs(point.modal_phasors_m.back()) > largest) {
      largest = std::abs(point.modal_phasors_m.back());
      largest_omega = point.omega_rad_s;
    }
  }
  // One contiguous three-solution band above ω0 (hardening); the upper branch
  // folds back just past its peak.
  ASSERT_GE(first_triple, 0) << "no fold found";
  for (int i = first_triple; i <= last_triple; ++i) EXPECT_EQ(sweep[i].modal_phasors_m.size(), 3u);
  EXPECT_GT(sweep[first_triple].omega_rad_s, omega0);
  EXPECT_GT(sweep[last_triple].omega_rad_s, peak_omega);
  EXPECT_LT(sweep[last_triple].omega_rad_s, peak_omega + 1e-3 * omega0);
  EXPECT_LT(std::abs(largest - peak) / peak, 1e-3);
  EXPECT_LT(std::abs(largest_omega - peak_omega) / omega0, 1e-4);
  std::printf("seed form, K3 = 1e5, C = %.2g, F = %.1f N: three solutions for %.5f <= Ω/ω0 <= %.5f\n", c, force,
              sweep[first_triple].omega_rad_s / omega0, sweep[last_triple].omega_rad_s / omega0);

  // The generalised form folds too, with its peak within a few per cent.
  const MultipleScalesModel generalised(testing::PaperBeam(), Support(0.0, 1.0e5, c), testing::kForcePosition_m);
  EXPECT_EQ(generalised.Solve(0.5 * (sweep[first_triple].omega_rad_s + peak_omega), force).size(), 3u);
  EXPECT_EQ(generalised.Solve(1.01 * peak_omega, force).size(), 1u);
}

TEST(MultipleScalesTest, SeedFormAgreesWithGeneralisedFormNearResonanceAtSmallAmplitude) {
  const auto support = Support(100.0, 3.0e4, 0.05);
  const MultipleScalesModel generalised(testing::PaperBeam(), support, testing::kForcePosition_m);
  const MultipleScalesModel seed(testing::PaperBeam(), support, testing::kForcePosition_m,
                                 {.harmonic_frequency = MultipleScalesHarmonicFrequency::kNatural});
  const double omega0 = generalised.NaturalFrequency_rad_s();
  for (double ratio : {0.997, 1.0, 1.003}) {
    const Complex a = generalised.Solve(ratio * omega0, 0.01).front();
    const Complex b = seed.Solve(ratio * omega0, 0.01).front();
    EXPECT_LT(std::abs(a - b) / std::abs(a), 0.005) << "Ω/ω0 " << ratio;
  }
}

TEST(MultipleScalesTest, RejectsInputsAUserCanGetWrong) {
  const auto beam = testing::PaperBeam();
  EXPECT_THROW(MultipleScalesModel(beam, Support(0.0, 1.0, -1.0), 0.57), std::invalid_argument);
  EXPECT_THROW(MultipleScalesModel(beam, Support(0.0, 1.0, 0.0), 0.9), std::invalid_argument);
  EXPECT_THROW(MultipleScalesModel(beam, Support(std::nan(""), 1.0, 0.0), 0.57), std::invalid_argument);
  const MultipleScalesModel model(beam, Support(0.0, 1.0, 0.0), 0.57);
  EXPECT_THROW(model.Solve(-1.0, 1.0), std::invalid_argument);
  EXPECT_THROW(model.Response(0.7, 1e-3, 300.0, 1.0), std::invalid_argument);
  EXPECT_THROW(model.Backbone_rad_s(-1.0), std::invalid_argument);
}

}  // namespace
}  // namespace beamid::hb
