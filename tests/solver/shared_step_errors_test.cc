// The information errors shared by a step's phasors add to the parameters'
// covariance (solver/estimation/shared_step_errors.h), checked by Monte Carlo
// of the linear least-squares problem it describes: residual errors drawn
// phasor by phasor with the whitened covariance I − Σ_m w_mi·w_miᵀ, plus one
// common error per step and source, so that each phasor's own block is I as
// the fit assumes. The estimates' scatter must match A⁻¹·B·A⁻¹, and differ
// from the A⁻¹ a phasor-by-phasor count gives.
#include <cmath>
#include <random>

#include <Eigen/Cholesky>
#include <Eigen/Dense>
#include <gtest/gtest.h>

#include "solver/estimation/shared_step_errors.h"

namespace beamid::solver {
namespace {

using Complex = std::complex<double>;

FitData ThreeStepsTwoChannelsTwoHarmonics(std::mt19937_64* rng) {
  std::normal_distribution<double> normal;
  FitData data;
  data.channels.resize(2);
  data.num_fit_harmonics = 2;
  data.steps.resize(3);
  for (FitStep& step : data.steps) {
    step.whitening.assign(2, {});
    for (auto& channel : step.whitening)
      for (int k = 0; k < 2; ++k) {
        Eigen::Matrix2d lower;
        lower << 1.0 + 0.3 * std::abs(normal(*rng)), 0.0, 0.2 * normal(*rng), 0.5 + 0.3 * std::abs(normal(*rng));
        channel.push_back(lower.inverse());
      }
    for (int m = 0; m < 2; ++m) {
      Eigen::MatrixXcd source(2, 2);
      for (int c = 0; c < 2; ++c)
        for (int k = 0; k < 2; ++k) source(c, k) = 0.3 * Complex(normal(*rng), normal(*rng));
      step.shared_errors.push_back(source);
    }
  }
  return data;
}

Eigen::Vector2d WhitenedShare(const FitStep& step, int source, int c, int k) {
  const Complex v = step.shared_errors[source](c, k);
  return step.whitening[c][k] * Eigen::Vector2d(v.real(), v.imag());
}

TEST(SharedErrorInformation, TheSandwichMatchesTheScatterOfLeastSquaresEstimatesUnderSharedErrors) {
  std::mt19937_64 rng(7);
  std::normal_distribution<double> normal;
  const FitData data = ThreeStepsTwoChannelsTwoHarmonics(&rng);
  const int rows = data.NumResiduals();
  ASSERT_EQ(rows, 24);
  constexpr int kParameters = 3;
  Eigen::MatrixXd j(rows, kParameters);
  for (int r = 0; r < rows; ++r)
    for (int p = 0; p < kParameters; ++p) j(r, p) = normal(rng);
  // The first parameter moves the phasors as the first source does (as a
  // gain moves them as the force's amplitude does): what the sources
  // then do to it does not average out over the phasors.
  for (std::size_t s = 0; s < data.steps.size(); ++s)
    for (int c = 0; c < 2; ++c)
      for (int k = 0; k < 2; ++k) j.block<2, 1>(2 * ((2 * s + c) * 2 + k), 0) += 3.0 * WhitenedShare(data.steps[s], 0, c, k);
  const Eigen::MatrixXd a = j.transpose() * j;
  const Eigen::MatrixXd a_inverse = a.inverse();
  const Eigen::MatrixXd predicted = a_inverse * (a + SharedErrorInformation(data, j)) * a_inverse;

  // Each phasor's own part of the error: I less the shared sources' blocks.
  std::vector<Eigen::Matrix2d> own_factor;
  for (const FitStep& step : data.steps)
    for (int c = 0; c < 2; ++c)
      for (int k = 0; k < 2; ++k) {
        Eigen::Matrix2d own = Eigen::Matrix2d::Identity();
        for (int m = 0; m < 2; ++m) own -= WhitenedShare(step, m, c, k) * WhitenedShare(step, m, c, k).transpose();
        ASSERT_GT(own.determinant(), 0.0);
        own_factor.push_back(own.llt().matrixL());
      }
  constexpr int kDraws = 200000;
  Eigen::MatrixXd scatter = Eigen::MatrixXd::Zero(kParameters, kParameters);
  const Eigen::MatrixXd solve = a_inverse * j.transpose();
  Eigen::VectorXd e(rows);
  for (int draw = 0; draw < kDraws; ++draw) {
    int phasor = 0;
    for (std::size_t s = 0; s < data.steps.size(); ++s) {
      const double shared[2] = {normal(rng), normal(rng)};
      for (int c = 0; c < 2; ++c)
        for (int k = 0; k < 2; ++k, ++phasor) {
          Eigen::Vector2d x = own_factor[phasor] * Eigen::Vector2d(normal(rng), normal(rng));
          for (int m = 0; m < 2; ++m) x += shared[m] * WhitenedShare(data.steps[s], m, c, k);
          e.segment<2>(2 * phasor) = x;
        }
    }
    const Eigen::VectorXd estimate = solve * e;
    scatter += estimate * estimate.transpose();
  }
  scatter /= kDraws;
  for (int p = 0; p < kParameters; ++p) {
    // Monte Carlo: a variance's relative σ is √(2/N) = 0.3 %.
    EXPECT_NEAR(scatter(p, p) / predicted(p, p), 1.0, 0.015) << "parameter " << p;
    for (int q = 0; q < p; ++q)
      EXPECT_NEAR(scatter(p, q) / std::sqrt(scatter(p, p) * scatter(q, q)),
                  predicted(p, q) / std::sqrt(predicted(p, p) * predicted(q, q)), 0.01)
          << p << ", " << q;
  }
  // The shared errors matter here: counting the phasors as independent
  // (A⁻¹) misses the scatter by more than the Monte Carlo's tolerance.
  double largest_miss = 0.0;
  for (int p = 0; p < kParameters; ++p) largest_miss = std::max(largest_miss, std::abs(scatter(p, p) / a_inverse(p, p) - 1.0));
  EXPECT_GT(largest_miss, 0.1);
}

TEST(SharedErrorInformation, NothingIsAddedWithoutSharedErrorsOrWithOnePhasorPerStep) {
  std::mt19937_64 rng(3);
  FitData data = ThreeStepsTwoChannelsTwoHarmonics(&rng);
  const Eigen::MatrixXd j = Eigen::MatrixXd::Random(data.NumResiduals(), 2);
  // One phasor per step carries each source: its own block, already in A.
  for (FitStep& step : data.steps)
    for (Eigen::MatrixXcd& source : step.shared_errors) {
      const Complex kept = source(1, 0);
      source.setZero();
      source(1, 0) = kept;
    }
  EXPECT_LT(SharedErrorInformation(data, j).norm(), 1e-14);
  for (FitStep& step : data.steps) step.shared_errors.clear();
  EXPECT_EQ(SharedErrorInformation(data, j).norm(), 0.0);
  EXPECT_THROW(SharedErrorInformation(data, Eigen::MatrixXd::Zero(4, 2)), std::invalid_argument);
}

}  // namespace
}  // namespace beamid::solver
