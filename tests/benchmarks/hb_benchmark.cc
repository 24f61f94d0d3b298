// Harmonic balance speed targets: one frequency response curve of 400 continuation
// points with H = 7 (target < 50 ms on one core) and one backbone of 200
// points (target < 20 ms), on the paper's beam with a cubic support.
#include <numbers>

#include <benchmark/benchmark.h>

#include "hb/backbone.h"
#include "hb/continuation.h"

namespace {

using namespace beamid::hb;

HarmonicBalance PaperBalance() {
  BeamProperties beam;
  beam.loss_factor = 1e-3;
  // Segments sized for the 7th harmonic of the highest frequency swept.
  return HarmonicBalance(LinearBeam({.beam = beam}, 0.570, {.max_frequency_hz = 8 * 60.0}),
                         PolynomialSupportLaw({.k1_Nm_rad = 150.43, .k2_Nm_rad2 = 2e3, .k3_Nm_rad3 = 4e5,
                                               .c_Nms_rad = 0.02}),
                         {.num_harmonics = 7});
}

void BM_FrequencyResponse400Points(benchmark::State& state) {
  const HarmonicBalance balance = PaperBalance();
  Eigen::VectorXcd force = Eigen::VectorXcd::Zero(2);
  force[1] = 2.0;
  const double omega = 2.0 * std::numbers::pi * 54.0;
  std::size_t points = 0;
  for (auto _ : state) {
    // A step small enough that the sweep 0.9–1.1 ω needs the full 400 points.
    const auto summary = TraceFrequencyResponse(
        balance, force,
        {.omega_start_rad_s = 0.9 * omega, .omega_end_rad_s = 1.1 * omega, .max_points = 400, .initial_step = 5e-4,
         .max_step = 5e-4});
    points = summary.points.size();
    benchmark::DoNotOptimize(summary.points.data());
  }
  state.counters["points"] = static_cast<double>(points);
}
BENCHMARK(BM_FrequencyResponse400Points)->Unit(benchmark::kMillisecond);

void BM_Backbone200Points(benchmark::State& state) {
  const HarmonicBalance balance = PaperBalance();
  std::size_t points = 0;
  for (auto _ : state) {
    const auto summary = TraceBackbone(balance, {.min_theta_amplitude_rad = 1e-5, .max_theta_amplitude_rad = 2e-2,
                                                 .num_points = 200});
    points = summary.points.size();
    benchmark::DoNotOptimize(summary.points.data());
  }
  state.counters["points"] = static_cast<double>(points);
}
BENCHMARK(BM_Backbone200Points)->Unit(benchmark::kMillisecond);

}  // namespace
