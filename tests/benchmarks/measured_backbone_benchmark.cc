// The measured backbone (solver/backbone/measured_backbone.h) on 20 levels ×
// 2000 steps of a hardening single-mode (Duffing-like) response, force
// controlled, below the fold, with 0.2 % noise: the whole analysis (jumps,
// phase resonances, peaks and half-power points with their propagated
// uncertainties, local fits, the cross-level model choice, regeneration,
// flags). Its memory must grow linearly with the steps (≤ 200 MB here; the
// former dense covariance of each level's inputs took (5n)² doubles, 800 MB
// per level): run it under /usr/bin/time -v for the peak RSS.
// The levels are made once, before the timings.
#include <cmath>
#include <complex>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>

#include "solver/backbone/measured_backbone.h"

namespace {

using namespace beamid;

constexpr double kTwoPi = 2 * std::numbers::pi;
constexpr double kOmega0 = kTwoPi * 50.0;
constexpr double kZeta = 0.01;
constexpr double kGamma = 6.33e10;  // ¾γa² shifts ω_n² by 12 % at 1 N's peak amplitude

// The amplitude on the one branch below the fold: u·|D(u)|² = F² has one root u = a².
double Amplitude(double omega, double force_N) {
  auto g = [&](double u) {
    const double re = kOmega0 * kOmega0 + 0.75 * kGamma * u - omega * omega, im = 2 * kZeta * kOmega0 * omega;
    return u * (re * re + im * im) - force_N * force_N;
  };
  double lo = 0.0, hi = 1.01 * std::pow(force_N / (2 * kZeta * kOmega0 * omega), 2);
  for (int it = 0; it < 200; ++it) {
    const double mid = 0.5 * (lo + hi);
    (g(mid) > 0 ? hi : lo) = mid;
  }
  return std::sqrt(0.5 * (lo + hi));
}

std::vector<signal::FirstHarmonicLevel> Levels(int num_levels, int num_steps) {
  std::mt19937 random(1);
  std::normal_distribution<double> normal;
  std::vector<signal::FirstHarmonicLevel> levels;
  for (int l = 0; l < num_levels; ++l) {
    const double force = 0.02 + 0.3 * l / (num_levels - 1);  // up to 0.32 N: below the fold (≈ 0.53 N)
    signal::FirstHarmonicLevel level{.label = "level_" + std::to_string(l), .source = "benchmark", .channel = "disp",
                                     .response_quantity = signal::Quantity::kDisplacement};
    for (int i = 0; i < num_steps; ++i) {
      const double f = 45.0 + 11.0 * i / (num_steps - 1), omega = kTwoPi * f;
      const double a = Amplitude(omega, force);
      const std::complex<double> d(kOmega0 * kOmega0 + 0.75 * kGamma * a * a - omega * omega, 2 * kZeta * kOmega0 * omega);
      std::complex<double> x = force / d;
      const double sigma = 2e-3 * std::abs(x) / std::sqrt(2.0);
      x += sigma * std::complex<double>(normal(random), normal(random));
      signal::FirstHarmonicPoint p{.frequency_hz = f};
      p.force.value = force;
      p.response.value = x;
      p.response.std_real = p.response.std_imag = sigma;
      level.points.push_back(p);
    }
    levels.push_back(std::move(level));
  }
  return levels;
}

void BM_MeasuredBackbone(benchmark::State& state) {
  const auto levels = Levels(static_cast<int>(state.range(0)), static_cast<int>(state.range(1)));
  for (auto _ : state) {
    const solver::MeasuredBackbone result = solver::AnalyseMeasuredBackbone(levels);
    benchmark::DoNotOptimize(result.levels.data());
  }
  state.counters["steps"] = static_cast<double>(state.range(0) * state.range(1));
}
// 20 × 2000 (the target); 20 × 500 and 20 × 1000 show how time grows with the steps.
BENCHMARK(BM_MeasuredBackbone)->Args({20, 500})->Args({20, 1000})->Args({20, 2000})->Unit(benchmark::kSecond)->Iterations(1);

}  // namespace
