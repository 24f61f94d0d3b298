// The support's loops from phasors of a linear support, computed by the
// full beam solve (LinearBeam::RespondToForce with the support spring and
// dashpot), not by the condensation the reconstruction uses: the energy per
// cycle is the dashpot's π·c·ω·|Θ₁|², the loops are ellipses, and a second
// harmonic of the rotation (driven by a moment at the support at 2ω) is
// reported as asymmetry.
#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "hb/linear_beam.h"
#include "solver/diagnosis/support_loops.h"
#include "tests/support/paper_setup.h"

namespace beamid::solver {
namespace {

using Complex = std::complex<double>;

constexpr double kK1 = 150.0, kC = 0.05;
constexpr double kSigma = 1e-4;  // σ of the acceleration phasors [m/s²]

// Accelerometer phasors of the paper's beam on a linear support under a force
// of `force_N` at ω, plus (harmonic 2) the response to a support moment
// `moment2_Nm` at 2ω — a rotation with an even harmonic.
FitData LinearSupportCampaign(double moment2_Nm) {
  const hb::LinearBeamModel model{.beam = testing::PaperBeam(), .support_stiffness_Nm_rad = kK1,
                                  .support_damping_Nms_rad = kC};
  const hb::LinearBeam beam(model, testing::kForcePosition_m);
  FitData data;
  data.beam = model.beam;
  data.force_position_m = testing::kForcePosition_m;
  data.num_fit_harmonics = 3;
  data.levels = {"low", "high"};
  for (int c = 0; c < 3; ++c)
    data.channels.push_back({.channel = "acc" + std::to_string(c + 1), .position_m = testing::kSensorPositions_m[c]});
  for (const auto& [level, force_N] : {std::pair{"low", 1.0}, std::pair{"high", 5.0}}) {
    for (double f_hz = 50.0; f_hz <= 58.0; f_hz += 2.0) {
      FitStep step;
      step.level = level;
      step.omega_rad_s = 2 * std::numbers::pi * f_hz;
      step.force_N = Eigen::VectorXcd::Zero(4);
      step.force_N[1] = force_N;
      step.measured = Eigen::MatrixXcd::Zero(3, 3);
      step.std_amplitude = Eigen::MatrixXd::Constant(3, 3, kSigma);
      step.whitening.assign(3, std::vector<Eigen::Matrix2d>(3, Eigen::Matrix2d::Identity() / kSigma));
      const double w = step.omega_rad_s;
      const hb::BeamDeflection forced = beam.RespondToForce(w);
      const hb::BeamDeflection moment = beam.RespondToSupportMoment(2 * w);
      for (int c = 0; c < 3; ++c) {
        const double x = testing::kSensorPositions_m[c];
        step.measured(c, 0) = -w * w * forced.Displacement_m(x) * force_N;
        step.measured(c, 1) = -4 * w * w * moment.Displacement_m(x) * moment2_Nm;
      }
      data.steps.push_back(std::move(step));
    }
  }
  return data;
}

const hb::LinearBeamModel kReference{.beam = testing::PaperBeam(), .support_stiffness_Nm_rad = kK1,
                                     .support_damping_Nms_rad = kC};

TEST(AnalyseSupportLoops, ALinearSupportDissipatesLikeItsDashpotAndDrawsEllipses) {
  const LoopEvidence loops = AnalyseSupportLoops(LinearSupportCampaign(0.0), kReference);
  ASSERT_EQ(loops.steps.size(), 10u);
  EXPECT_EQ(loops.num_steps_used, 10);
  for (const LoopStep& s : loops.steps) {
    EXPECT_NEAR(s.equivalent_damping_Nms_rad, kC, 1e-6 * kC) << s.omega_rad_s;
    EXPECT_NEAR(s.dissipated_energy_J, s.viscous_energy_J, 1e-6 * s.viscous_energy_J);
    EXPECT_LT(s.moment_harmonic_ratio, 1e-9);
    EXPECT_LT(s.theta_even_fraction, 1e-9);
  }
  EXPECT_NEAR(loops.area_exponent, 2.0, 1e-6);
  EXPECT_NEAR(loops.mean_equivalent_damping_Nms_rad, kC, 1e-6 * kC);
  EXPECT_FALSE(loops.dissipation_not_viscous);
  EXPECT_FALSE(loops.non_elliptic);
  EXPECT_FALSE(loops.hysteretic_shape);
  EXPECT_FALSE(loops.asymmetric);
}

TEST(AnalyseSupportLoops, AnEvenHarmonicOfTheRotationIsReportedAsAsymmetry) {
  const LoopEvidence loops = AnalyseSupportLoops(LinearSupportCampaign(0.01), kReference);
  EXPECT_TRUE(loops.asymmetric);
  for (const LoopStep& s : loops.steps) EXPECT_GT(s.theta_even_fraction, 1e-4);
  // The applied moment at 2ω is beyond the linear support (as a k2·θ² term
  // would be): the loops are not ellipses.
  EXPECT_TRUE(loops.non_elliptic);
  for (const LoopStep& s : loops.steps) EXPECT_GT(s.moment_harmonic_ratio, 1e-3);
}

}  // namespace
}  // namespace beamid::solver
