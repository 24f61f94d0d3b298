// Monte Carlo efficiency of the estimator (interpolated-DFT start, Gauss–
// Newton frequency, least-squares phasors) against the Cramér–Rao bound of
// the full multi-harmonic model with unknown frequency, computed numerically
// from its Fisher information (tests/signal/synthetic_signal.h), at SNR 20,
// 40 and 60 dB (SNR = fundamental power / noise variance). Random
// non-integer numbers of periods, random phases, harmonics down to -60 dB.
// Checks: variance / CRB within [0.8, 1.2] for Re/Im of every harmonic, for
// amplitude and phase of every harmonic well above the noise (|X|/√CRB > 20)
// and for the frequency; the reported standard uncertainties within 20 % of
// the Monte Carlo scatter.
#include <cmath>
#include <complex>
#include <cstdio>
#include <random>

#include <gtest/gtest.h>

#include "signal/frequency_estimator.h"
#include "signal/harmonic_fit.h"
#include "tests/signal/synthetic_signal.h"

namespace beamid::signal {
namespace {

using testing::AmplitudeBound;
using testing::CramerRaoBound;
using testing::PhaseBound;
using testing::RandomTone;
using testing::Synthesize;
using testing::Tone;

constexpr int kRuns = 1000;     // sample variance within ±4.5 % (1σ) of the truth
constexpr double kMaxRatio = 1.2;   // the requirement
constexpr double kMinRatio = 0.8;   // nothing beats the bound: lower means a broken test
constexpr int kHarmonics = 5;
constexpr double kHighSnrAmplitudeRatio = 20.0;

struct Accumulator {
  double sum = 0.0, sum2 = 0.0;
  int count = 0;
  void Add(double v) {
    sum += v;
    sum2 += v * v;
    ++count;
  }
  double Variance() const { return (sum2 - sum * sum / count) / (count - 1); }
};

class CramerRaoTest : public ::testing::TestWithParam<double> {};

TEST_P(CramerRaoTest, VarianceReachesTheBoundAndUncertaintyMatchesScatter) {
  const double snr_db = GetParam();
  std::mt19937 rng(static_cast<unsigned>(1000 + snr_db));
  std::uniform_real_distribution<double> frequency(40.0, 60.0);
  const int n = 4096;
  Tone tone = RandomTone(rng, kHarmonics, frequency(rng));
  tone.sample_rate_hz = 5120.0;
  const double amplitude = std::abs(tone.phasors[0]);
  const double noise_variance = 0.5 * amplitude * amplitude / std::pow(10.0, snr_db / 10.0);
  const Eigen::VectorXd clean = Synthesize(tone, n);
  const Eigen::MatrixXd crb = CramerRaoBound(tone, n, noise_variance);
  std::printf("SNR %.0f dB: f = %.4f Hz, %.3f periods\n", snr_db, tone.frequency_hz, n * tone.frequency_hz / 5120.0);

  std::normal_distribution<double> noise(0.0, std::sqrt(noise_variance));
  std::vector<Accumulator> re(kHarmonics), im(kHarmonics), amp(kHarmonics), phase(kHarmonics);
  std::vector<double> reported_re(kHarmonics, 0.0), reported_im(kHarmonics, 0.0);
  Accumulator omega;
  Eigen::VectorXd x(n);
  for (int run = 0; run < kRuns; ++run) {
    for (int i = 0; i < n; ++i) x(i) = clean(i) + noise(rng);
    const FrequencyEstimate f = EstimateFrequency(x, tone.sample_rate_hz, 50.0);
    const HarmonicFit fit = FitHarmonics(x, tone.sample_rate_hz, f.frequency_hz, kHarmonics);
    omega.Add(2.0 * std::numbers::pi * f.frequency_hz);
    for (int k = 1; k <= kHarmonics; ++k) {
      const std::complex<double> value = fit.channels[0].phasors(k - 1);
      const std::complex<double> truth = tone.phasors[static_cast<std::size_t>(k - 1)];
      re[k - 1].Add(value.real());
      im[k - 1].Add(value.imag());
      amp[k - 1].Add(std::abs(value));
      phase[k - 1].Add(testing::WrapPhase(std::arg(value) - std::arg(truth)));
      reported_re[k - 1] += fit.channels[0].covariances[static_cast<std::size_t>(k - 1)](0, 0) / kRuns;
      reported_im[k - 1] += fit.channels[0].covariances[static_cast<std::size_t>(k - 1)](1, 1) / kRuns;
    }
  }
  auto check = [&](const char* what, int k, double variance, double bound) {
    const double ratio = variance / bound;
    std::printf("  %-9s k=%d  var/CRB = %.3f\n", what, k, ratio);
    EXPECT_LT(ratio, kMaxRatio) << what << " k=" << k << " at " << snr_db << " dB";
    EXPECT_GT(ratio, kMinRatio) << what << " k=" << k << " at " << snr_db << " dB";
  };
  check("frequency", 0, omega.Variance(), crb(2 * kHarmonics + 1, 2 * kHarmonics + 1));
  for (int k = 1; k <= kHarmonics; ++k) {
    check("Re X", k, re[k - 1].Variance(), crb(2 * k - 1, 2 * k - 1));
    check("Im X", k, im[k - 1].Variance(), crb(2 * k, 2 * k));
    const std::complex<double> truth = tone.phasors[static_cast<std::size_t>(k - 1)];
    if (std::abs(truth) > kHighSnrAmplitudeRatio * std::sqrt(crb(2 * k - 1, 2 * k - 1))) {
      check("amplitude", k, amp[k - 1].Variance(), AmplitudeBound(crb, truth, k));
      check("phase", k, phase[k - 1].Variance(), PhaseBound(crb, truth, k));
    }
    // Reported standard uncertainty against the scatter it predicts.
    for (auto [name, reported, scatter] : {std::tuple{"std Re", reported_re[k - 1], re[k - 1].Variance()},
                                           std::tuple{"std Im", reported_im[k - 1], im[k - 1].Variance()}}) {
      const double ratio = std::sqrt(reported / scatter);
      std::printf("  %-9s k=%d  reported/scatter = %.3f\n", name, k, ratio);
      EXPECT_NEAR(ratio, 1.0, 0.2) << name << " k=" << k << " at " << snr_db << " dB";
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Snr, CramerRaoTest, ::testing::Values(20.0, 40.0, 60.0));

// The measurement behind the estimator choice (docs/signal.md): three
// candidates on the same records,
//   A. interpolated Hann DFT: frequency from the two-bin interpolation,
//      phasors X_k = 2·Σw_n x_n e^{−ikω̂τ_n}/Σw_n (Hann window);
//   B. least squares at the interpolated-DFT frequency (no refinement);
//   C. least squares at the Gauss–Newton frequency (the chosen estimator).
// Noise-free bias of the -60 dB harmonic and var/CRB at 40 dB SNR. The test
// asserts what the choice rests on: A's window costs variance and leaks into
// weak harmonics, B's frequency misses the bound, C reaches it.
TEST(EstimatorChoiceTest, OnlyLeastSquaresWithGaussNewtonReachesTheBound) {
  std::mt19937 rng(77);
  const int n = 4096;
  const double rate_hz = 5120.0;
  Tone tone = RandomTone(rng, kHarmonics, 51.37);
  tone.sample_rate_hz = rate_hz;
  const Eigen::VectorXd clean = Synthesize(tone, n);
  const double noise_variance = 0.5 * std::norm(tone.phasors[0]) / 1e4;  // 40 dB
  const Eigen::MatrixXd crb = CramerRaoBound(tone, n, noise_variance);

  auto hann_phasors = [&](const Eigen::VectorXd& x, double f_hz) {
    Eigen::VectorXcd phasors(kHarmonics);
    double sum_w = 0.0;
    for (int i = 0; i < n; ++i) sum_w += 0.5 - 0.5 * std::cos(2.0 * std::numbers::pi * i / n);
    for (int k = 1; k <= kHarmonics; ++k) {
      std::complex<double> sum = 0.0;
      for (int i = 0; i < n; ++i) {
        const double w = 0.5 - 0.5 * std::cos(2.0 * std::numbers::pi * i / n);
        const double tau = (i - 0.5 * (n - 1)) / rate_hz;
        sum += w * x(i) * std::polar(1.0, -2.0 * std::numbers::pi * k * f_hz * tau);
      }
      phasors(k - 1) = 2.0 * sum / sum_w;
    }
    return phasors;
  };
  struct Result {
    Accumulator omega, re1, amp1, phase1;
    double bias_weakest = 0.0;
  };
  Result results[3];
  auto estimate = [&](const Eigen::VectorXd& x, int method, double& f_hz) {
    const double f_dft = InterpolatedDftFrequency(x, rate_hz, 50.0, 0.05);
    if (method == 0) {
      f_hz = f_dft;
      return hann_phasors(x, f_dft);
    }
    f_hz = method == 1 ? f_dft : EstimateFrequency(x, rate_hz, 50.0).frequency_hz;
    return Eigen::VectorXcd(FitHarmonics(x, rate_hz, f_hz, kHarmonics).channels[0].phasors);
  };
  const std::complex<double> weakest = tone.phasors.back();  // -60 dB
  for (int method = 0; method < 3; ++method) {
    double f_hz = 0.0;
    const Eigen::VectorXcd noise_free = estimate(clean, method, f_hz);
    results[method].bias_weakest = std::abs(noise_free(kHarmonics - 1) - weakest) / std::abs(weakest);
  }
  std::normal_distribution<double> noise(0.0, std::sqrt(noise_variance));
  Eigen::VectorXd x(n);
  for (int run = 0; run < 500; ++run) {
    for (int i = 0; i < n; ++i) x(i) = clean(i) + noise(rng);
    for (int method = 0; method < 3; ++method) {
      double f_hz = 0.0;
      const Eigen::VectorXcd phasors = estimate(x, method, f_hz);
      results[method].omega.Add(2.0 * std::numbers::pi * f_hz);
      results[method].re1.Add(phasors(0).real());
      results[method].amp1.Add(std::abs(phasors(0)));
      results[method].phase1.Add(std::arg(phasors(0)));
    }
  }
  const char* names[3] = {"A interpolated Hann DFT", "B LS at interpolated-DFT f", "C LS at Gauss-Newton f"};
  double ratios[3][4];
  for (int method = 0; method < 3; ++method) {
    const Result& r = results[method];
    ratios[method][0] = r.omega.Variance() / crb(2 * kHarmonics + 1, 2 * kHarmonics + 1);
    ratios[method][1] = r.re1.Variance() / crb(1, 1);
    ratios[method][2] = r.amp1.Variance() / AmplitudeBound(crb, tone.phasors[0], 1);
    ratios[method][3] = r.phase1.Variance() / PhaseBound(crb, tone.phasors[0], 1);
    std::printf("%-28s var/CRB: frequency %.2f, Re X1 %.2f, |X1| %.2f, arg X1 %.2f; noise-free error of the -60 dB "
                "harmonic %.1e\n",
                names[method], ratios[method][0], ratios[method][1], ratios[method][2], ratios[method][3],
                r.bias_weakest);
  }
  EXPECT_GT(ratios[0][2], 1.3);                  // A: the window's noise bandwidth
  EXPECT_GT(results[0].bias_weakest, 1e-4);      // A: leakage into a -60 dB harmonic
  EXPECT_GT(ratios[1][0], 1.3);                  // B: frequency off the bound
  for (double ratio : ratios[2]) EXPECT_LT(ratio, kMaxRatio);
  EXPECT_LT(results[2].bias_weakest, 1e-6);
}

}  // namespace
}  // namespace beamid::signal
