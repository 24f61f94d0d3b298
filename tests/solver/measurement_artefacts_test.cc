// The measurement artefacts' data corrections and parameter estimates
// (solver/diagnosis/measurement_artefacts.h). CorrectedData must be an exact
// transformation: the whitened residual of the artefact's model on the
// original data, W((1+g)Ŷ − Y) for a gain g and W(e^{−ikωτ}Ŷ − Y) for a
// delay τ, has the same norm as W'(Ŷ − Y') on the corrected data, for any
// model phasors Ŷ. EstimateGain and EstimatePhaseDelay must recover a known g
// and τ from phasors made as (1+g)·Ŷ or e^{−ikωτ}·Ŷ plus Gaussian noise of
// the whitening's covariance (Ŷ arbitrary smooth complex numbers, no model:
// a check of the estimators against a known truth), with a standard
// uncertainty that matches their scatter over noise draws (400 draws: the
// sample spread is known to ±3.5 %, so the reported std must lie within 20 %).
// The clock error scales every step's ω and nothing else, and
// EstimateClockError recovers a known ε from phasors of the harmonic-balance
// model evaluated at the scaled frequencies.
#include "solver/diagnosis/measurement_artefacts.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdio>
#include <numbers>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include <Eigen/LU>
#include <gtest/gtest.h>

#include "solver/diagnosis/fitted_model.h"
#include "solver/estimation/fit_problem.h"
#include "solver/estimation/model_family.h"
#include "solver/estimation/model_structure.h"
#include "tests/support/synthetic_fit_data.h"

namespace beamid::solver {
namespace {

using Complex = std::complex<double>;

// Random whitening matrices (full, not symmetric: the identities hold for any
// L⁻¹) and random model phasors for every step of `data`.
std::vector<Eigen::MatrixXcd> Scramble(FitData& data, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<Eigen::MatrixXcd> model;
  for (auto& s : data.steps) {
    for (auto& channel : s.whitening)
      for (auto& w : channel) w = Eigen::Matrix2d::Identity() * 80.0 + 30.0 * Eigen::Matrix2d::NullaryExpr([&] { return u(rng); });
    Eigen::MatrixXcd y(static_cast<Eigen::Index>(data.channels.size()), data.num_fit_harmonics);
    for (Eigen::Index j = 0; j < y.size(); ++j) y(j) = Complex(u(rng), u(rng));
    model.push_back(y);
  }
  return model;
}

Eigen::Vector2d Whiten(const Eigen::Matrix2d& w, Complex z) { return w * Eigen::Vector2d(z.real(), z.imag()); }

// Σ |W(Ŷ − Y)|² over every channel, harmonic and step; `artefact` applied to
// Ŷ of `channel` (the artefact's model of the recorded phasors).
template <typename Artefact>
double ModelChiSquare(const FitData& data, const std::vector<Eigen::MatrixXcd>& model, int channel, const Artefact& artefact) {
  double chi2 = 0.0;
  for (std::size_t i = 0; i < data.steps.size(); ++i)
    for (int c = 0; c < static_cast<int>(data.channels.size()); ++c)
      for (int k = 1; k <= data.num_fit_harmonics; ++k) {
        const FitStep& s = data.steps[i];
        const Complex y_hat = c == channel ? artefact(model[i](c, k - 1), k, s.omega_rad_s) : model[i](c, k - 1);
        chi2 += Whiten(s.whitening[c][k - 1], y_hat - s.measured(c, k - 1)).squaredNorm();
      }
  return chi2;
}

const auto kPlain = [](Complex y, int, double) { return y; };

TEST(CorrectedData, GainCorrectionIsExact) {
  FitData data = testing::SyntheticFitData();
  std::mt19937 rng(1);
  const std::vector<Eigen::MatrixXcd> model = Scramble(data, rng);
  for (int channel : {0, 1})
    for (double g : {0.05, -0.2, 1.5}) {
      const FitData corrected = CorrectedData(data, {.kind = ArtefactKind::kSensorGain, .channel = channel, .value = g});
      const double original = ModelChiSquare(data, model, channel, [&](Complex y, int, double) { return (1.0 + g) * y; });
      const double on_corrected = ModelChiSquare(corrected, model, -1, kPlain);
      EXPECT_NEAR(on_corrected, original, 1e-12 * original) << "channel " << channel << ", g " << g;
      // And not trivially: without the artefact the misfit differs.
      EXPECT_GT(std::abs(ModelChiSquare(data, model, -1, kPlain) - original), 1e-3 * original);
      // Per residual too, and the other channel untouched.
      for (std::size_t i = 0; i < data.steps.size(); ++i)
        for (int k = 1; k <= data.num_fit_harmonics; ++k) {
          const FitStep& s = data.steps[i];
          const FitStep& t = corrected.steps[i];
          const Eigen::Vector2d a = Whiten(s.whitening[channel][k - 1], (1.0 + g) * model[i](channel, k - 1) - s.measured(channel, k - 1));
          const Eigen::Vector2d b = Whiten(t.whitening[channel][k - 1], model[i](channel, k - 1) - t.measured(channel, k - 1));
          EXPECT_LT((a - b).norm(), 1e-12 * a.norm());
          const int other = 1 - channel;
          EXPECT_EQ(t.measured(other, k - 1), s.measured(other, k - 1));
          EXPECT_EQ(t.whitening[other][k - 1], s.whitening[other][k - 1]);
          EXPECT_NEAR(t.std_amplitude(channel, k - 1), s.std_amplitude(channel, k - 1) / (1.0 + g), 1e-15);
        }
    }
}

TEST(CorrectedData, PhaseDelayCorrectionIsExact) {
  FitData data = testing::SyntheticFitData();
  std::mt19937 rng(2);
  const std::vector<Eigen::MatrixXcd> model = Scramble(data, rng);
  for (int channel : {0, 1})
    for (double tau : {2e-4, -1e-3, 3e-3}) {
      const FitData corrected =
          CorrectedData(data, {.kind = ArtefactKind::kSensorPhaseDelay, .channel = channel, .value = tau});
      const auto delayed = [&](Complex y, int k, double omega) { return std::polar(1.0, -k * omega * tau) * y; };
      const double original = ModelChiSquare(data, model, channel, delayed);
      const double on_corrected = ModelChiSquare(corrected, model, -1, kPlain);
      EXPECT_NEAR(on_corrected, original, 1e-12 * original) << "channel " << channel << ", tau " << tau;
      EXPECT_GT(std::abs(ModelChiSquare(data, model, -1, kPlain) - original), 1e-3 * original);
      // The sign matters: the opposite delay is another misfit.
      const auto advanced = [&](Complex y, int k, double omega) { return std::polar(1.0, k * omega * tau) * y; };
      EXPECT_GT(std::abs(ModelChiSquare(data, model, channel, advanced) - original), 1e-3 * original);
      for (std::size_t i = 0; i < data.steps.size(); ++i)
        for (int k = 1; k <= data.num_fit_harmonics; ++k) {
          const FitStep& s = data.steps[i];
          const FitStep& t = corrected.steps[i];
          const Eigen::Vector2d a = Whiten(s.whitening[channel][k - 1], delayed(model[i](channel, k - 1), k, s.omega_rad_s) - s.measured(channel, k - 1));
          const Eigen::Vector2d b = Whiten(t.whitening[channel][k - 1], model[i](channel, k - 1) - t.measured(channel, k - 1));
          EXPECT_LT((a - b).norm(), 1e-12 * a.norm());
          // A delay changes no amplitude.
          EXPECT_NEAR(std::abs(t.measured(channel, k - 1)), std::abs(s.measured(channel, k - 1)), 1e-14);
          const int other = 1 - channel;
          EXPECT_EQ(t.measured(other, k - 1), s.measured(other, k - 1));
          EXPECT_EQ(t.whitening[other][k - 1], s.whitening[other][k - 1]);
        }
    }
}

bool SameSteps(const FitStep& a, const FitStep& b) {
  if (a.measured != b.measured || a.force_N != b.force_N || a.omega_rad_s != b.omega_rad_s) return false;
  for (std::size_t c = 0; c < a.whitening.size(); ++c)
    for (std::size_t k = 0; k < a.whitening[c].size(); ++k)
      if (a.whitening[c][k] != b.whitening[c][k]) return false;
  return true;
}

TEST(CorrectedData, PositionMovesOnlyThatChannel) {
  const FitData data = testing::SyntheticFitData();
  const FitData corrected = CorrectedData(data, {.kind = ArtefactKind::kSensorPosition, .channel = 1, .value = 0.004});
  EXPECT_DOUBLE_EQ(corrected.channels[1].position_m, data.channels[1].position_m + 0.004);
  EXPECT_EQ(corrected.channels[0].position_m, data.channels[0].position_m);
  EXPECT_EQ(corrected.force_position_m, data.force_position_m);
  ASSERT_EQ(corrected.steps.size(), data.steps.size());
  for (std::size_t i = 0; i < data.steps.size(); ++i) EXPECT_TRUE(SameSteps(corrected.steps[i], data.steps[i])) << i;
}

TEST(CorrectedData, AnOutlyingStepLosesItsWeightAndNothingElseChanges) {
  FitData data = testing::SyntheticFitData();
  std::mt19937 rng(3);
  Scramble(data, rng);
  const FitData corrected = CorrectedData(data, {.kind = ArtefactKind::kOutlyingStep, .step = 1});
  ASSERT_EQ(corrected.steps.size(), data.steps.size());
  EXPECT_TRUE(SameSteps(corrected.steps[0], data.steps[0]));
  EXPECT_TRUE(SameSteps(corrected.steps[2], data.steps[2]));
  const FitStep& s = data.steps[1];
  const FitStep& t = corrected.steps[1];
  EXPECT_EQ(t.measured, s.measured);
  for (std::size_t c = 0; c < s.whitening.size(); ++c)
    for (std::size_t k = 0; k < s.whitening[c].size(); ++k)
      EXPECT_LT((t.whitening[c][k] - 1e-6 * s.whitening[c][k]).norm(), 1e-15 * s.whitening[c][k].norm()) << c << " " << k;
}

TEST(CorrectedData, AClockErrorScalesEveryStepsFrequencyAndNothingElse) {
  FitData data = testing::SyntheticFitData();
  std::mt19937 rng(4);
  Scramble(data, rng);
  for (double e : {0.004, -0.02}) {
    const FitData corrected = CorrectedData(data, {.kind = ArtefactKind::kClockError, .value = e});
    ASSERT_EQ(corrected.steps.size(), data.steps.size());
    for (std::size_t i = 0; i < data.steps.size(); ++i) {
      const FitStep& s = data.steps[i];
      const FitStep& t = corrected.steps[i];
      // The read ω is the true one/(1 + ε): the model's is the read one times 1 + ε.
      EXPECT_EQ(t.omega_rad_s, s.omega_rad_s * (1.0 + e)) << i;
      // Phasors in m/s² and their uncertainties do not depend on the time axis.
      FitStep same_frequency = t;
      same_frequency.omega_rad_s = s.omega_rad_s;
      EXPECT_TRUE(SameSteps(same_frequency, s)) << i;
      EXPECT_EQ(t.std_amplitude, s.std_amplitude);
    }
    for (std::size_t c = 0; c < data.channels.size(); ++c)
      EXPECT_EQ(corrected.channels[c].position_m, data.channels[c].position_m);
  }
  EXPECT_EQ(ArtefactName(data, {.kind = ArtefactKind::kClockError, .value = 0.005}), "clock_error");
}

TEST(ClockErrorRigCheck, SaysHowFarTheFrequenciesReadOffInPercentAndPpm) {
  const FitData data = testing::SyntheticFitData();
  const std::string fast = ArtefactRigCheck(data, {.kind = ArtefactKind::kClockError, .value = 0.005});
  // 1 − 1/1.005 = 0.4975 %.
  EXPECT_NE(fast.find("the frequencies read 0.50 % low (the clock runs 5000 ppm fast)"), std::string::npos) << fast;
  const std::string slow = ArtefactRigCheck(data, {.kind = ArtefactKind::kClockError, .value = -0.002});
  EXPECT_NE(slow.find("0.20 % high (the clock runs 2000 ppm slow)"), std::string::npos) << slow;
}

// The stated frequencies against the read ones: a generator's ppm offset
// is no clock error's evidence, a misread step does not move the median, and
// without stated frequencies there is none.
TEST(ClockErrorFromStatedFrequencies, IsTheMedianOffsetOfTheStatedFromTheReadFrequencies) {
  FitData data = testing::SyntheticFitData();
  EXPECT_EQ(ClockErrorFromStatedFrequencies(data), 0.0);
  constexpr double kClock = 0.002;
  for (FitStep& s : data.steps) s.nominal_frequency_hz = s.FrequencyHz() * (1.0 + kClock);
  EXPECT_NEAR(ClockErrorFromStatedFrequencies(data), kClock, 1e-15);
  data.steps[1].nominal_frequency_hz = 2.0 * data.steps[1].FrequencyHz();  // a misread step
  EXPECT_NEAR(ClockErrorFromStatedFrequencies(data), kClock, 1e-15);
  for (FitStep& s : data.steps) s.nominal_frequency_hz = s.FrequencyHz() * (1.0 - 25e-6);
  EXPECT_NEAR(ClockErrorFromStatedFrequencies(data), -25e-6, 1e-12);
}

// ---------------------------------------------------------------------------
// The clock error's estimate against a model evaluated at known scaled
// frequencies: the paper's beam and support, harmonic balance.

FittedModel ModelAt(const FitData& data, const ModelStructure& structure) {
  const ModelFamily& family = HarmonicBalanceFamily();
  const std::unique_ptr<FitProblem> problem = family.MakeProblem(data, structure, ModelOptions{.num_harmonics = 5});
  const std::vector<double> values = structure.Values();
  return FittedModel(data, family, structure, 5, values, problem->FeasiblePoint(values), values);
}

TEST(EstimateClockError, RecoversAKnownClockErrorFromAModelAtTheTrueFrequencies) {
  ModelStructure structure = PolynomialModel({.k1_Nm_rad = 150.0, .k3_Nm_rad3 = 3e5, .c_Nms_rad = 0.05});
  structure.linear.push_back(LossFactor(2e-4));
  for (double e : {0.004, -0.003}) {
    SCOPED_TRACE("clock error " + std::to_string(e));
    FitData read = testing::SyntheticFitData();
    // The recorded phasors are the beam's at the true frequencies, read (1 + ε) low.
    const FitData at_truth = CorrectedData(read, {.kind = ArtefactKind::kClockError, .value = e});
    const std::vector<Eigen::MatrixXcd> recorded = ModelAt(at_truth, structure).Phasors(at_truth);
    for (std::size_t i = 0; i < read.steps.size(); ++i) read.steps[i].measured = recorded[i];
    const FittedModel model = ModelAt(read, structure);
    // Not trivially: at the read frequencies the model misses them by far more than σ.
    const std::vector<Eigen::MatrixXcd> unscaled = model.Phasors(read);
    double largest_miss = 0.0;
    for (std::size_t i = 0; i < read.steps.size(); ++i)
      largest_miss = std::max(largest_miss, (unscaled[i] - recorded[i]).cwiseAbs().maxCoeff());
    EXPECT_GT(largest_miss, 100.0 * read.steps[0].std_amplitude(0, 0));

    const ArtefactEstimate exact = EstimateClockError(read, model);
    std::printf("noise-free: eps = %.9f ± %.2g (truth %.4f)\n", exact.value, exact.std, e);
    EXPECT_GT(exact.std, 0.0);
    EXPECT_NEAR(exact.value, e, 1e-6 * std::abs(e));

    // With noise of the whitening's σ the truth lies within 3σ of the estimate.
    std::mt19937 rng(11);
    std::normal_distribution<double> normal;
    for (auto& s : read.steps)
      for (Eigen::Index j = 0; j < s.measured.size(); ++j)
        s.measured(j) += s.std_amplitude(j) * Complex(normal(rng), normal(rng));
    const ArtefactEstimate noisy = EstimateClockError(read, model);
    std::printf("noisy: eps = %.9f ± %.2g\n", noisy.value, noisy.std);
    EXPECT_LT(std::abs(noisy.value - e), 3.0 * noisy.std);
    EXPECT_LT(noisy.std, 0.05 * std::abs(e));
  }
}

// ---------------------------------------------------------------------------
// The estimators against a known g and τ.

constexpr int kSteps = 24;
constexpr int kChannels = 2;
constexpr int kHarmonics = 3;

// Smooth model phasors over 50–58 Hz (a resonance-like curve per channel and
// harmonic, no physics) and per-phasor anisotropic noise covariances L·Lᵀ.
struct Truth {
  FitData data;
  std::vector<Eigen::MatrixXcd> model;
  std::vector<std::vector<std::vector<Eigen::Matrix2d>>> cholesky;  // [step][channel][k-1]: L
};

Truth MakeTruth() {
  Truth t;
  t.data.channels = {{.channel = "acc1", .position_m = 0.1}, {.channel = "acc2", .position_m = 0.3}};
  t.data.num_fit_harmonics = kHarmonics;
  t.data.levels = {"low"};
  std::mt19937 rng(17);
  std::uniform_real_distribution<double> u(0.5, 1.5), angle(-1.0, 1.0);
  for (int i = 0; i < kSteps; ++i) {
    const double f = 50.0 + 8.0 * i / (kSteps - 1);
    FitStep s{.level = "low", .file = "s" + std::to_string(i) + ".csv", .omega_rad_s = 2.0 * std::numbers::pi * f};
    Eigen::MatrixXcd y(kChannels, kHarmonics);
    std::vector<std::vector<Eigen::Matrix2d>> l(kChannels, std::vector<Eigen::Matrix2d>(kHarmonics));
    s.whitening.assign(kChannels, std::vector<Eigen::Matrix2d>(kHarmonics));
    s.std_amplitude.resize(kChannels, kHarmonics);
    for (int c = 0; c < kChannels; ++c)
      for (int k = 1; k <= kHarmonics; ++k) {
        const double r = f / (54.0 + c);
        y(c, k - 1) = (c + 1.0) * std::pow(0.1, k - 1) / Complex(1.0 - r * r, 0.03 * k);
        // σ ~ 1 % of the phasor, anisotropic and correlated.
        const double sigma = 0.01 * std::abs(y(c, k - 1));
        Eigen::Matrix2d lk;
        lk << sigma * u(rng), 0.0, sigma * 0.5 * angle(rng), sigma * u(rng);
        l[c][k - 1] = lk;
        s.whitening[c][k - 1] = lk.inverse();
        s.std_amplitude(c, k - 1) = sigma;
      }
    t.model.push_back(y);
    t.cholesky.push_back(l);
    t.data.steps.push_back(s);
  }
  return t;
}

// Measured phasors: the artefact applied to the model, plus noise N(0, L·Lᵀ).
template <typename Artefact>
void Measure(Truth& t, int channel, const Artefact& artefact, std::mt19937& rng) {
  std::normal_distribution<double> normal;
  for (std::size_t i = 0; i < t.data.steps.size(); ++i) {
    FitStep& s = t.data.steps[i];
    s.measured.resize(kChannels, kHarmonics);
    for (int c = 0; c < kChannels; ++c)
      for (int k = 1; k <= kHarmonics; ++k) {
        const Complex y = t.model[i](c, k - 1);
        const Eigen::Vector2d e = t.cholesky[i][c][k - 1] * Eigen::Vector2d(normal(rng), normal(rng));
        s.measured(c, k - 1) = (c == channel ? artefact(y, k, s.omega_rad_s) : y) + Complex(e(0), e(1));
      }
  }
}

struct Scatter {
  double mean = 0.0, spread = 0.0, mean_std = 0.0, worst_z = 0.0;
};

template <typename Estimator, typename Artefact>
Scatter OverNoiseDraws(Truth t, int channel, double truth, const Estimator& estimate, const Artefact& artefact) {
  constexpr int kDraws = 400;
  std::mt19937 rng(99 + channel);
  double sum = 0.0, sum2 = 0.0, sum_std = 0.0, worst = 0.0;
  for (int d = 0; d < kDraws; ++d) {
    Measure(t, channel, artefact, rng);
    const ArtefactEstimate e = estimate(t.data, t.model, channel);
    EXPECT_GT(e.std, 0.0);
    sum += e.value;
    sum2 += e.value * e.value;
    sum_std += e.std;
    worst = std::max(worst, std::abs(e.value - truth) / e.std);
  }
  Scatter s;
  s.mean = sum / kDraws;
  s.spread = std::sqrt(std::max(0.0, (sum2 - kDraws * s.mean * s.mean) / (kDraws - 1)));
  s.mean_std = sum_std / kDraws;
  s.worst_z = worst;
  return s;
}

TEST(EstimateGain, RecoversAKnownGainWithAnHonestUncertainty) {
  constexpr double g = 0.05;
  const auto gain = [](Complex y, int, double) { return (1.0 + g) * y; };
  for (int channel : {0, 1}) {
    Truth t = MakeTruth();
    std::mt19937 rng(5);
    Measure(t, channel, gain, rng);
    const ArtefactEstimate e = EstimateGain(t.data, t.model, channel);
    std::printf("channel %d: g = %.6f ± %.2g (truth %.2f)\n", channel, e.value, e.std, g);
    EXPECT_LT(std::abs(e.value - g), 3.0 * e.std);
    EXPECT_LT(e.std, 0.05 * g);  // a measurement that resolves it
    // The other channel, which has no gain error, reads none.
    const ArtefactEstimate other = EstimateGain(t.data, t.model, 1 - channel);
    EXPECT_LT(std::abs(other.value), 3.0 * other.std);

    const Scatter s = OverNoiseDraws(MakeTruth(), channel, g, EstimateGain, gain);
    std::printf("  over 400 draws: mean %.6f, spread %.3g, reported std %.3g, worst |z| %.2f\n", s.mean, s.spread,
                s.mean_std, s.worst_z);
    EXPECT_LT(std::abs(s.mean - g), 3.0 * s.spread / std::sqrt(400.0));
    EXPECT_LT(s.mean_std, 1.2 * s.spread);
    EXPECT_GT(s.mean_std, s.spread / 1.2);
  }
}

TEST(EstimatePhaseDelay, RecoversAKnownDelayWithAnHonestUncertainty) {
  constexpr double tau = 2e-4;  // 0.2 ms: up to 0.2 rad at the third harmonic
  const auto delay = [](Complex y, int k, double omega) { return std::polar(1.0, -k * omega * tau) * y; };
  for (int channel : {0, 1}) {
    Truth t = MakeTruth();
    std::mt19937 rng(6);
    Measure(t, channel, delay, rng);
    const ArtefactEstimate e = EstimatePhaseDelay(t.data, t.model, channel);
    std::printf("channel %d: tau = %.6g ± %.2g s (truth %.2g)\n", channel, e.value, e.std, tau);
    EXPECT_LT(std::abs(e.value - tau), 3.0 * e.std);
    EXPECT_LT(e.std, 0.05 * tau);
    const ArtefactEstimate other = EstimatePhaseDelay(t.data, t.model, 1 - channel);
    EXPECT_LT(std::abs(other.value), 3.0 * other.std);

    const Scatter s = OverNoiseDraws(MakeTruth(), channel, tau, EstimatePhaseDelay, delay);
    std::printf("  over 400 draws: mean %.6g, spread %.3g, reported std %.3g, worst |z| %.2f\n", s.mean, s.spread,
                s.mean_std, s.worst_z);
    EXPECT_LT(std::abs(s.mean - tau), 3.0 * s.spread / std::sqrt(400.0));
    EXPECT_LT(s.mean_std, 1.2 * s.spread);
    EXPECT_GT(s.mean_std, s.spread / 1.2);
  }
}

}  // namespace
}  // namespace beamid::solver
