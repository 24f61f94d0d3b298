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
// (the others hold no truth).
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

void BM_DiagnosisCoverage(benchmark::State& state, const std::string& cause_name, solver::PhasorUncertainty weighting,
                          beamid::testing::CoverageSettling settling = beamid::testing::CoverageSettling::kAsThePaper) {
  const beamid::testing::ConcealedCause cause = beamid::testing::MakeConcealedCause(cause_name, settling);
  beamid::testing::DiagnosisCoverageStudy study;
  for (auto _ : state) study = beamid::testing::RunDiagnosisCoverageStudy(cause, weighting, kRealisations, 7000);
  ReportCoverage(state, study.coverage);
  state.counters["named"] = static_cast<double>(study.named) / study.coverage.realisations;
}

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

BENCHMARK_CAPTURE(BM_DiagnosisCoverage, sensor_gain_relative_floor, "sensor_gain",
                  solver::PhasorUncertainty::kRelativeFloor)->Iterations(1)->Unit(benchmark::kSecond);
BENCHMARK_CAPTURE(BM_DiagnosisCoverage, sensor_gain_propagated, "sensor_gain", solver::PhasorUncertainty::kPropagated)
    ->Iterations(1)->Unit(benchmark::kSecond);
BENCHMARK_CAPTURE(BM_DiagnosisCoverage, sensor_gain_exact_propagated, "sensor_gain",
                  solver::PhasorUncertainty::kPropagated, beamid::testing::CoverageSettling::kTight)
    ->Iterations(1)->Unit(benchmark::kSecond);
BENCHMARK_CAPTURE(BM_DiagnosisCoverage, friction_relative_floor, "friction", solver::PhasorUncertainty::kRelativeFloor)
    ->Iterations(1)->Unit(benchmark::kSecond);
BENCHMARK_CAPTURE(BM_DiagnosisCoverage, friction_propagated, "friction", solver::PhasorUncertainty::kPropagated)
    ->Iterations(1)->Unit(benchmark::kSecond);

}  // namespace
