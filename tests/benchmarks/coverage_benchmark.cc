// Coverage of identify's 95 % intervals (tests/support/coverage_study.h):
// 50 realisations of the measurement noise on one simulation of the paper's
// campaign (15 steps per level), for each physics and each phasor weighting.
// Counters per parameter: coverage (the fraction of intervals that hold the
// truth; 0.95 when calibrated), mean_z (bias in σ) and rms_z (1 when the σ
// are right); mean_chi2 is the fits' mean reduced χ²; window_start_rms_s how
// far the noise moves where each step's analysed part starts (rms over the
// steps of its σ over the realisations; 0: the same part in every copy).
// Runs 56–173 s per capture on 2 cores.
// BM_DiagnosisCoverage does the same for the model a diagnosis names on a
// campaign with a concealed cause (a fault of the recording, friction),
// 3 levels × 9 steps; `named` is the share of realisations that name it
// (the others hold no truth). On the exact physics the named fault's
// study takes 200 realisations; the named friction's is also simulated anew
// for each realisation (CoverageRecords::kSimulatedPerRealisation).
#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include <benchmark/benchmark.h>

#include "tests/support/coverage_study.h"

namespace {

using namespace beamid;

constexpr int kRealisations = 50;

void ReportCoverage(benchmark::State& state, const beamid::testing::CoverageStudy& study) {
  for (std::size_t j = 0; j < study.parameters.size(); ++j) {
    const std::string& name = study.parameters[j].name;
    state.counters["coverage_" + name] = study.Coverage(j);
    state.counters["mean_z_" + name] = study.MeanZ(j);  // over the realisations that estimated it
    state.counters["rms_z_" + name] = study.RmsZ(j);
  }
  state.counters["mean_chi2"] = study.MeanReducedChiSquare();
  state.counters["window_start_rms_s"] = study.WindowStartRms_s();
}

void BM_Coverage(benchmark::State& state, const std::string& physics_name, solver::PhasorUncertainty weighting,
                 beamid::testing::CoverageSettling settling = beamid::testing::CoverageSettling::kAsThePaper) {
  const beamid::testing::CoveragePhysics physics = beamid::testing::MakeCoveragePhysics(physics_name, settling);
  beamid::testing::CoverageStudy study;
  for (auto _ : state) study = beamid::testing::RunCoverageStudy(physics, {.uncertainty = weighting}, kRealisations, 1000);
  ReportCoverage(state, study);
}

void BM_DiagnosisCoverage(benchmark::State& state, const std::string& cause_name,
                          const beamid::testing::DiagnosisCoverageOptions& options,
                          beamid::testing::ConcealedPhysics physics = beamid::testing::ConcealedPhysics::kAsThePaper) {
  const beamid::testing::ConcealedCause cause = beamid::testing::MakeConcealedCause(cause_name, physics);
  beamid::testing::DiagnosisCoverageStudy study;
  for (auto _ : state) study = beamid::testing::RunDiagnosisCoverageStudy(cause, options);
  ReportCoverage(state, study.coverage);
  state.counters["named"] = static_cast<double>(study.named) / study.coverage.realisations;
}

// Which step sets the damping of one realisation (the argument: its seed
// offset, as in BM_Coverage): the modal-law campaign is fitted again without
// each step in turn. Counters: c's z with every step, and without the step
// whose removal moves c most (in the full fit's σ), that step's frequency
// and level index, and how much c's σ grows without it. Realisation 10,
// c at z = −4.1 (its tightly settled twin reads +0.1), is the example.
void BM_StepInfluenceOnDamping(benchmark::State& state) {
  const beamid::testing::CoveragePhysics physics = beamid::testing::MakeCoveragePhysics("modal_loss_factor");
  const auto [steps, campaign] = beamid::testing::SimulateCoverageCampaign(physics);
  constexpr std::size_t kC = 3;  // c in the structure's order (k1, k2, k3, c, η_m)
  const double truth = physics.truth[kC];
  for (auto _ : state) {
    const signal::PhasorSet phasors =
        beamid::testing::MeasureAgain(physics.scenario, steps, campaign, 1000 + state.range(0));
    const solver::FitData all = solver::MakeFitData(
        campaign, phasors, {.channels = {"acc1", "acc2"}, .uncertainty = solver::PhasorUncertainty::kPropagated});
    const solver::ParameterEstimate c = solver::Identify(all, physics.structure, {}).parameters.at(kC);
    state.counters["c_z"] = (c.value - truth) / c.std;
    double largest_move = -1.0;
    for (std::size_t i = 0; i < all.steps.size(); ++i) {
      solver::FitData without = all;
      without.steps.erase(without.steps.begin() + static_cast<std::ptrdiff_t>(i));
      const solver::ParameterEstimate c_without = solver::Identify(without, physics.structure, {}).parameters.at(kC);
      const double move = std::abs(c_without.value - c.value) / c.std;
      if (move <= largest_move) continue;
      largest_move = move;
      state.counters["c_z_without_step"] = (c_without.value - truth) / c.std;
      state.counters["std_ratio_without_step"] = c_without.std / c.std;
      state.counters["step_hz"] = all.steps[i].omega_rad_s / (2.0 * std::numbers::pi);
      state.counters["step_level"] = static_cast<double>(
          std::find(all.levels.begin(), all.levels.end(), all.steps[i].level) - all.levels.begin());
    }
  }
}

BENCHMARK(BM_StepInfluenceOnDamping)->Arg(10)->Iterations(1)->Unit(benchmark::kSecond);

BENCHMARK_CAPTURE(BM_Coverage, loss_factor_relative_floor, "loss_factor", solver::PhasorUncertainty::kRelativeFloor)
    ->Iterations(1)->Unit(benchmark::kSecond);
BENCHMARK_CAPTURE(BM_Coverage, loss_factor_propagated, "loss_factor", solver::PhasorUncertainty::kPropagated)
    ->Iterations(1)->Unit(benchmark::kSecond);
BENCHMARK_CAPTURE(BM_Coverage, modal_loss_factor_propagated, "modal_loss_factor",
                  solver::PhasorUncertainty::kPropagated)->Iterations(1)->Unit(benchmark::kSecond);
BENCHMARK_CAPTURE(BM_Coverage, modal_loss_factor_settled_propagated, "modal_loss_factor",
                  solver::PhasorUncertainty::kPropagated, beamid::testing::CoverageSettling::kTight)
    ->Iterations(1)->Unit(benchmark::kSecond);
BENCHMARK_CAPTURE(BM_Coverage, rayleigh_relative_floor, "rayleigh", solver::PhasorUncertainty::kRelativeFloor)
    ->Iterations(1)->Unit(benchmark::kSecond);
BENCHMARK_CAPTURE(BM_Coverage, rayleigh_propagated, "rayleigh", solver::PhasorUncertainty::kPropagated)
    ->Iterations(1)->Unit(benchmark::kSecond);
BENCHMARK_CAPTURE(BM_Coverage, rayleigh_settled_propagated, "rayleigh", solver::PhasorUncertainty::kPropagated,
                  beamid::testing::CoverageSettling::kTight)->Iterations(1)->Unit(benchmark::kSecond);

using beamid::testing::ConcealedPhysics;
using beamid::testing::CoverageCandidates;
using beamid::testing::CoverageRecords;
constexpr solver::PhasorUncertainty kFloor = solver::PhasorUncertainty::kRelativeFloor;

BENCHMARK_CAPTURE(BM_DiagnosisCoverage, none_exact_propagated, "none", {}, ConcealedPhysics::kExact)
    ->Iterations(1)->Unit(benchmark::kSecond);
BENCHMARK_CAPTURE(BM_DiagnosisCoverage, sensor_gain_relative_floor, "sensor_gain", {.weighting = kFloor})
    ->Iterations(1)->Unit(benchmark::kSecond);
BENCHMARK_CAPTURE(BM_DiagnosisCoverage, sensor_gain_propagated, "sensor_gain", {})
    ->Iterations(1)->Unit(benchmark::kSecond);
// 200 realisations: 50 read the gain's rms z anywhere in 0.77–1.13.
BENCHMARK_CAPTURE(BM_DiagnosisCoverage, sensor_gain_exact_propagated, "sensor_gain", {.realisations = 200},
                  ConcealedPhysics::kExact)
    ->Iterations(1)->Unit(benchmark::kSecond);
BENCHMARK_CAPTURE(BM_DiagnosisCoverage, friction_relative_floor, "friction", {.weighting = kFloor})
    ->Iterations(1)->Unit(benchmark::kSecond);
BENCHMARK_CAPTURE(BM_DiagnosisCoverage, friction_propagated, "friction", {})->Iterations(1)->Unit(benchmark::kSecond);
BENCHMARK_CAPTURE(BM_DiagnosisCoverage, friction_exact_propagated, "friction", {}, ConcealedPhysics::kExact)
    ->Iterations(1)->Unit(benchmark::kSecond);
// The same with each realisation simulated anew (CoverageRecords): the
// slipping steps never settle, and one simulation's non-periodic part, shared
// by every realisation above, biases k2 by −0.8 of its σ.
BENCHMARK_CAPTURE(BM_DiagnosisCoverage, friction_exact_resimulated_propagated, "friction",
                  {.records = CoverageRecords::kSimulatedPerRealisation}, ConcealedPhysics::kExact)
    ->Iterations(1)->Unit(benchmark::kSecond);
// The same with the cause the only candidate (CoverageCandidates), as
// coverage_slow_test runs it.
BENCHMARK_CAPTURE(BM_DiagnosisCoverage, friction_exact_resimulated_alone_propagated, "friction",
                  {.records = CoverageRecords::kSimulatedPerRealisation,
                   .candidates = CoverageCandidates::kTheCauseAlone},
                  ConcealedPhysics::kExact)
    ->Iterations(1)->Unit(benchmark::kSecond);

}  // namespace
