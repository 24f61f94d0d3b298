// The modal loss factor of the exact beam (hb/matched_modal_loss.h: residues
// of the continuous beam's receptances, a correction of its condensation on θ)
// against another formulation: the finite-element beam of the time simulator
// (hb/fe_beam.h), every one of its modes damped as the simulator damps them,
// c_j = η·ω_j²/(k_j·ω), and its receptances summed over all modes,
//     H(Ω) = Σ_j φ_j·φ_jᵀ / (ω_j² + iΩ·c_j − Ω²).
#include <cmath>
#include <complex>
#include <iostream>
#include <numbers>
#include <vector>

#include <Eigen/Eigenvalues>
#include <gtest/gtest.h>

#include "hb/fe_beam.h"
#include "hb/harmonic_balance.h"
#include "hb/linear_beam.h"
#include "hb/matched_modal_loss.h"

namespace beamid::hb {
namespace {

using Complex = std::complex<double>;

constexpr double kForcePosition_m = 0.45;
const std::vector<double> kPositions_m = {0.10, 0.30, 0.57};
constexpr double kModalLossFactor = 0.05;  // large, so that the laws differ clearly
constexpr int kHarmonics = 5;
// Cubic elements put mode j's frequency ~(j·h/L)⁴ high; with 160 elements
// and the exact beam's modes to 5 kHz the receptances agree within 4.2e-4
// (the 4th harmonic of the 52 Hz drive), 1e-5 or better at the fundamental.
constexpr double kTolerance = 1e-3;

LinearAttachments Attachments() {
  LinearAttachments a;
  a.clamp_rotational_stiffness_Nm_rad = 4.0e4;
  a.point_masses = {{0.30, 0.020}, {kForcePosition_m, 0.035}};
  return a;
}

// The receptances between θ, the force point and the positions: row/column 0
// is θ, 1 the force point, 2… the positions.
using Receptances = Eigen::MatrixXcd;

// From the condensation on θ (H_θθ = 1/D, H_θF = B/D, H_xθ = b/D,
// H_xF = a + b·B/D); H_FF and H_xx' are not part of it and are left 0.
Receptances FromCondensed(const LinearHarmonics& linear, int k) {
  const auto n = static_cast<Eigen::Index>(kPositions_m.size());
  Receptances h = Receptances::Zero(n + 2, n + 2);
  const Complex d = linear.rotational_stiffness[k], b = linear.blocked_moment_per_force[k];
  h(0, 0) = 1.0 / d;
  h(0, 1) = h(1, 0) = b / d;
  for (Eigen::Index x = 0; x < n; ++x) {
    h(2 + x, 0) = h(0, 2 + x) = linear.displacement_per_rotation(x, k) / d;
    h(2 + x, 1) = h(1, 2 + x) =
        linear.displacement_per_force(x, k) + linear.displacement_per_rotation(x, k) * b / d;
  }
  return h;
}

class FiniteElementModes {
 public:
  FiniteElementModes() {
    std::vector<double> nodes = kPositions_m;
    nodes.push_back(kForcePosition_m);
    const FeBeam fe(BeamProperties{}, Attachments(), nodes, {.min_elements = 160});
    const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> modes(fe.Stiffness(), fe.Mass());
    omega_squared_ = modes.eigenvalues();
    std::vector<int> dofs = {fe.SupportRotationDof(), fe.DeflectionDof(kForcePosition_m)};
    for (double x : kPositions_m) dofs.push_back(fe.DeflectionDof(x));
    shapes_.resize(static_cast<Eigen::Index>(dofs.size()), omega_squared_.size());
    for (std::size_t r = 0; r < dofs.size(); ++r) shapes_.row(static_cast<Eigen::Index>(r)) = modes.eigenvectors().row(dofs[r]);
  }

  // With the simulator's damping (hb/time_simulator.cc, MatchLossFactorAt).
  Receptances At(double omega_rad_s, int k) const {
    const double frequency = k * omega_rad_s;
    Eigen::VectorXcd modal(omega_squared_.size());
    for (Eigen::Index j = 0; j < omega_squared_.size(); ++j) {
      const double harmonic = std::max(1.0, std::round(std::sqrt(omega_squared_[j]) / omega_rad_s));
      const double c = kModalLossFactor * omega_squared_[j] / (harmonic * omega_rad_s);
      modal[j] = 1.0 / Complex(omega_squared_[j] - frequency * frequency, frequency * c);
    }
    Receptances h = shapes_.cast<Complex>() * modal.asDiagonal() * shapes_.transpose().cast<Complex>();
    h(1, 1) = 0.0;
    h.bottomRightCorner(h.rows() - 2, h.cols() - 2).setZero();
    return h;
  }

 private:
  Eigen::VectorXd omega_squared_;
  Eigen::MatrixXd shapes_;
};

double RelativeDifference(const Receptances& a, const Receptances& b) {
  double worst = 0.0;
  for (Eigen::Index i = 0; i < a.rows(); ++i)
    for (Eigen::Index j = 0; j < a.cols(); ++j)
      if (b(i, j) != 0.0) worst = std::max(worst, std::abs(a(i, j) - b(i, j)) / std::abs(b(i, j)));
  return worst;
}

LinearHarmonics Exact(double loss_factor, double modal_loss_factor, double omega_rad_s) {
  BeamProperties beam;
  beam.loss_factor = loss_factor;
  beam.modal_loss_factor = modal_loss_factor;
  // Exact in the band a fit asks for, 1.5·(H + 1) times the drive.
  const LinearBeamOptions band{.max_frequency_hz = 1.5 * (kHarmonics + 1) * omega_rad_s / (2.0 * std::numbers::pi)};
  const LinearBeam exact(LinearBeamModel{.beam = beam, .attachments = Attachments()}, kForcePosition_m, band);
  return ComputeLinearHarmonics(exact, omega_rad_s, kHarmonics, kPositions_m);
}

// Drives near the first θ-free mode (≈ 51 Hz: modes 1, 2, 3 driven by the
// harmonics 1, 3, 7) and at half of it (mode 1 driven by the 2nd harmonic).
class MatchedModalLossAgainstFiniteElements : public ::testing::TestWithParam<double> {};

TEST_P(MatchedModalLossAgainstFiniteElements, ReceptancesAgreeAtEveryHarmonicWhereTheLossFactorsDoNot) {
  static const FiniteElementModes fe;
  const double omega = 2.0 * std::numbers::pi * GetParam();
  const LinearHarmonics modal = Exact(0.0, kModalLossFactor, omega);
  const LinearHarmonics uniform = Exact(kModalLossFactor, 0.0, omega);
  double worst_uniform = 0.0;
  for (int k = 1; k <= kHarmonics; ++k) {
    const Receptances expected = fe.At(omega, k);
    EXPECT_LT(RelativeDifference(FromCondensed(modal, k), expected), kTolerance) << "harmonic " << k;
    worst_uniform = std::max(worst_uniform, RelativeDifference(FromCondensed(uniform, k), expected));
    std::cout << "harmonic " << k << ": modal loss factor " << RelativeDifference(FromCondensed(modal, k), expected)
              << ", loss factor " << RelativeDifference(FromCondensed(uniform, k), expected) << "\n";
  }
  // The comparison can tell the two laws apart: a loss factor η in every
  // mode misses the simulator's damping by many times the tolerance.
  EXPECT_GT(worst_uniform, 10 * kTolerance);
}

INSTANTIATE_TEST_SUITE_P(DriveFrequencies, MatchedModalLossAgainstFiniteElements, ::testing::Values(52.0, 26.0));

TEST(MatchedModalLoss, ModesAreMassNormalisedAndCoverTheBandOfFiveKilohertzAtLeast) {
  const LinearBeamModel model{.beam = BeamProperties{.modal_loss_factor = 1e-3}, .attachments = Attachments()};
  const MatchedModalLoss law(model, kForcePosition_m, {.max_frequency_hz = 500.0});
  const LinearBeam beam(LinearBeamModel{.beam = BeamProperties{}, .attachments = Attachments()}, kForcePosition_m);
  const std::vector<double> expected = beam.NaturalFrequencies_rad_s(law.num_modes() + 1);
  const double band_rad_s = 2.0 * std::numbers::pi * 5000.0;
  ASSERT_GE(law.num_modes(), 5);
  for (int j = 0; j < law.num_modes(); ++j) EXPECT_NEAR(law.natural_frequencies_rad_s()[j], expected[j], 1e-9 * expected[j]);
  EXPECT_LE(law.natural_frequencies_rad_s().back(), band_rad_s);
  EXPECT_GT(expected.back(), band_rad_s);
  // The static flexibility at θ is the sum of every mode's φ_j'(L)²/ω_j²,
  // whose terms fall like 1/j²: the modes in the band hold most of it, and
  // never more.
  const MatchedModalLoss::ModeValues values = law.At(kPositions_m);
  double sum = 0.0;
  for (int j = 0; j < law.num_modes(); ++j) sum += values.rotation[j] * values.rotation[j] / (expected[j] * expected[j]);
  const double flexibility = 1.0 / beam.CondenseOnSupportRotation(0.0, {}).rotational_stiffness_Nm_rad.real();
  EXPECT_LT(sum, flexibility);
  EXPECT_GT(sum, 0.9 * flexibility);
}

// The modes are kept per undamped beam (a fit rebuilds the beam at every
// η_m): a beam that differs in anything they depend on (its modulus, a
// point mass, the clamp) must get its own, one that differs in its damping
// alone the same. Mode j of a beam whose E is 1 % higher lies √1.01 higher.
TEST(MatchedModalLossTest, ModesAreSharedBetweenDampingsAndNeverBetweenBeams) {
  LinearBeamModel model{.beam = {.modal_loss_factor = 1e-4}, .attachments = Attachments()};
  const MatchedModalLoss first(model, kForcePosition_m, {});
  model.beam.modal_loss_factor = 3e-4;
  model.beam.loss_factor = 1e-4;
  const MatchedModalLoss damped_otherwise(model, kForcePosition_m, {});
  EXPECT_EQ(&first.natural_frequencies_rad_s(), &damped_otherwise.natural_frequencies_rad_s());

  // The clamp's spring does not scale with E: a rigid clamp here.
  LinearBeamModel rigid{.beam = {.modal_loss_factor = 1e-4}};
  const MatchedModalLoss rigid_modes(rigid, kForcePosition_m, {});
  rigid.beam.youngs_modulus_Pa *= 1.01;
  const MatchedModalLoss stiffer_modes(rigid, kForcePosition_m, {});
  ASSERT_GE(stiffer_modes.num_modes(), 3);
  for (int j = 0; j < 3; ++j)
    EXPECT_NEAR(stiffer_modes.natural_frequencies_rad_s()[j] / rigid_modes.natural_frequencies_rad_s()[j],
                std::sqrt(1.01), 1e-9) << "mode " << j;

  LinearBeamModel heavier = model;
  heavier.attachments.point_masses[0].mass_kg += 0.01;
  const MatchedModalLoss heavier_modes(heavier, kForcePosition_m, {});
  EXPECT_LT(heavier_modes.natural_frequencies_rad_s()[0], first.natural_frequencies_rad_s()[0]);

  LinearBeamModel clamped = model;
  clamped.attachments.clamp_rotational_stiffness_Nm_rad *= 2.0;
  const MatchedModalLoss clamped_modes(clamped, kForcePosition_m, {});
  EXPECT_GT(clamped_modes.natural_frequencies_rad_s()[0], first.natural_frequencies_rad_s()[0]);
}

}  // namespace
}  // namespace beamid::hb
