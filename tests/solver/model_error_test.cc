// The residual model error's estimate (solver/estimation/model_error.h)
// against its closed form where every phasor has the same σ and magnitude,
// and its 95 % interval against a Monte Carlo of phasors with unequal,
// correlated covariances and magnitudes; the χ² quantile it rests on
// against tabulated values.
#include <cmath>
#include <random>
#include <vector>

#include <Eigen/Cholesky>
#include <gtest/gtest.h>

#include "solver/estimation/chi_square.h"
#include "solver/estimation/model_error.h"

namespace beamid::solver {
namespace {

TEST(ChiSquareUpperQuantile, MatchesTabulatedPoints) {
  // Abramowitz & Stegun, table 26.8.
  EXPECT_NEAR(ChiSquareUpperQuantile(0.05, 1.0), 3.841459, 1e-6);
  EXPECT_NEAR(ChiSquareUpperQuantile(0.025, 10.0), 20.483177, 1e-6);
  EXPECT_NEAR(ChiSquareUpperQuantile(0.975, 100.0), 74.221927, 1e-5);
  EXPECT_NEAR(ChiSquareUpperTail(ChiSquareUpperQuantile(0.3, 1234.5), 1234.5), 0.3, 1e-10);
  EXPECT_THROW(ChiSquareUpperQuantile(0.0, 3.0), std::invalid_argument);
  EXPECT_THROW(ChiSquareUpperQuantile(0.5, 0.0), std::invalid_argument);
}

TEST(ModelError, EqualsTheClosedFormWhenEveryPhasorHasTheSameSigmaAndMagnitude) {
  // Q(ε) = Σ|r|²/(σ² + ε²a²) = ν  ⇒  ε² = (Σ|r|²/ν − σ²)/a².
  const double sigma = 2e-3, magnitude = 0.7, dof = 37.0;
  std::vector<ModelErrorPhasor> phasors;
  double sum_r2 = 0.0;
  for (int i = 0; i < 20; ++i) {
    const Eigen::Vector2d r(3e-3 * std::sin(1.0 + i), 4e-3 * std::cos(2.0 * i));
    sum_r2 += r.squaredNorm();
    phasors.push_back({.residual = r, .covariance = sigma * sigma * Eigen::Matrix2d::Identity(), .scale = magnitude});
  }
  const ModelErrorEstimate e = EstimateModelError(phasors, dof);
  const double expected = std::sqrt((sum_r2 / dof - sigma * sigma) / (magnitude * magnitude));
  EXPECT_NEAR(e.relative, expected, 1e-10 * expected);
  EXPECT_NEAR(e.chi_square, sum_r2 / (sigma * sigma), 1e-9 * e.chi_square);
  const double lower =
      std::sqrt((sum_r2 / ChiSquareUpperQuantile(0.025, dof) - sigma * sigma) / (magnitude * magnitude));
  const double upper =
      std::sqrt((sum_r2 / ChiSquareUpperQuantile(0.975, dof) - sigma * sigma) / (magnitude * magnitude));
  EXPECT_NEAR(e.lower_95, lower, 1e-10 * lower);
  EXPECT_NEAR(e.upper_95, upper, 1e-10 * upper);
  EXPECT_LT(e.lower_95, e.relative);
  EXPECT_GT(e.upper_95, e.relative);
}

TEST(ModelError, IsZeroWhenTheStatedSigmaHoldTheResiduals) {
  std::vector<ModelErrorPhasor> phasors;
  for (int i = 0; i < 10; ++i)
    phasors.push_back({.residual = Eigen::Vector2d(0.9, -0.3), .covariance = Eigen::Matrix2d::Identity(), .scale = 5.0});
  // Q(0) = 10·0.9 = 9 against ν = 20: nothing beyond the noise.
  const ModelErrorEstimate e = EstimateModelError(phasors, 20.0);
  EXPECT_EQ(e.relative, 0.0);
  EXPECT_EQ(e.lower_95, 0.0);
  EXPECT_EQ(e.upper_95, 0.0);  // Q(0) = 9 is below χ²(20)'s 2.5 % point (9.59)
  EXPECT_NEAR(e.chi_square, 9.0, 1e-12);
}

TEST(ModelError, IntervalHoldsTheTrueErrorNineteenTimesInTwentyAndTheEstimateIsCentred) {
  // Phasors with correlated, unequal noise covariances and magnitudes
  // spanning a decade, plus a relative model error comparable to the noise.
  std::mt19937_64 rng(20261128);
  std::normal_distribution<double> normal;
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  const double truth = 2e-3;
  const int num_phasors = 150, draws = 400;
  int covered = 0;
  double sum_estimate2 = 0.0;
  for (int d = 0; d < draws; ++d) {
    std::vector<ModelErrorPhasor> phasors;
    for (int i = 0; i < num_phasors; ++i) {
      const double scale = std::pow(10.0, uniform(rng));
      const double s1 = 1e-3 * (0.5 + uniform(rng)), s2 = 1e-3 * (0.5 + uniform(rng)), rho = 0.8 * (2.0 * uniform(rng) - 1.0);
      Eigen::Matrix2d c;
      c << s1 * s1, rho * s1 * s2, rho * s1 * s2, s2 * s2;
      const Eigen::Matrix2d total = c + std::pow(truth * scale, 2) * Eigen::Matrix2d::Identity();
      const Eigen::Matrix2d root = total.llt().matrixL();
      phasors.push_back({.residual = root * Eigen::Vector2d(normal(rng), normal(rng)), .covariance = c, .scale = scale});
    }
    const ModelErrorEstimate e = EstimateModelError(phasors, 2.0 * num_phasors);
    covered += e.lower_95 <= truth && truth <= e.upper_95;
    sum_estimate2 += e.relative * e.relative;
  }
  // Binomial σ of the coverage over 400 draws: 1.1 %.
  const double coverage = static_cast<double>(covered) / draws;
  EXPECT_GE(coverage, 0.915);
  EXPECT_LE(coverage, 0.985);
  // The moment estimate of ε² is centred (a few % at 300 residuals).
  EXPECT_NEAR(std::sqrt(sum_estimate2 / draws), truth, 0.05 * truth);
}

TEST(ModelError, RefusesWhatItCannotEstimate) {
  const std::vector<ModelErrorPhasor> zero_scale = {
      {.residual = Eigen::Vector2d(1.0, 1.0), .covariance = Eigen::Matrix2d::Identity(), .scale = 0.0}};
  EXPECT_THROW(EstimateModelError(zero_scale, 2.0), std::invalid_argument);
  const std::vector<ModelErrorPhasor> singular = {
      {.residual = Eigen::Vector2d(1.0, 1.0), .covariance = Eigen::Matrix2d::Zero(), .scale = 1.0}};
  EXPECT_THROW(EstimateModelError(singular, 2.0), std::invalid_argument);
  EXPECT_THROW(EstimateModelError({}, 0.0), std::invalid_argument);
}

}  // namespace
}  // namespace beamid::solver
