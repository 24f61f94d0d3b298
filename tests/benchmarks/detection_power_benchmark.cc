// Detection power of the diagnosis: for each cause it names, how often it
// names that cause at each size of the effect, over noise realisations of
// one time-domain simulation per size (the paper's set-up, 3 levels × 9
// steps, the scenario's noise; tests/support/simulated_campaign.h). The
// false-alarm rate these rates go with is false_alarm_benchmark's.
// Counters, per size: `named@<size>` the share of realisations whose
// selected model is the cause (a tie that holds it counts), with the 95 %
// Wilson interval (`low@`, `high@`). The smallest size named in at least
// 90 % is the detection threshold the docs quote (docs/diagnose.md).
// Diagnosed under the relative floor, as the docs' rows were measured,
// but where a capture's name ends in _propagated.
// One benchmark per cause; each runs sizes × realisations diagnoses of
// 5–30 s on 2 cores (the longer where faults and physics compete, or where
// a cause is named and its pairs and damping laws refitted), 6–33 min a
// cause: select with --benchmark_filter.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>
#include <fmt/core.h>
#include <nlohmann/json.hpp>

#include "solver/diagnosis/diagnosis.h"
#include "tests/support/proof_diagnosis.h"
#include "tests/support/simulated_campaign.h"
#include "tests/support/wilson_interval.h"

namespace {

using namespace beamid;
// tests/support/, not GoogleTest's namespace of the same name.
namespace support = beamid::testing;

constexpr int kRealisations = 20;

struct Cause {
  std::string label;                 // the size's unit in the counters' names
  std::vector<double> sizes;
  // Puts an effect of this size into the paper set-up's scenario.
  std::function<void(nlohmann::json&, double)> conceal;
  // The selected names that count as naming it.
  std::vector<std::string> names;
};

bool Named(const solver::DiagnosisResult& result, const std::vector<std::string>& names) {
  for (const std::string& selected : result.selected)
    if (std::find(names.begin(), names.end(), selected) != names.end()) return true;
  return false;
}

void BM_DetectionPower(benchmark::State& state, const Cause& cause,
                       solver::PhasorUncertainty weighting = solver::PhasorUncertainty::kRelativeFloor) {
  for (auto _ : state) {
    for (const double size : cause.sizes) {
      nlohmann::json json = support::PaperSetUpScenario();
      cause.conceal(json, size);
      const hb::Scenario scenario = hb::ParseScenario(json.dump(), "detection power scenario");
      const std::vector<hb::SimulatedStep> steps = support::SimulateSteps(scenario);
      const support::ExtractedCampaign written = support::WriteAndExtract(scenario, steps, 1, "beamid_power");
      int named = 0;
      for (int r = 0; r < kRealisations; ++r) {
        const signal::PhasorSet phasors = support::MeasureAgain(scenario, steps, written.campaign, 6000 + r);
        const solver::DiagnosisResult result =
            support::DiagnoseProofData(support::MakeProofData(written.campaign, phasors, {.uncertainty = weighting}));
        named += Named(result, cause.names);
        std::string selected;
        for (const std::string& s : result.selected) selected += (selected.empty() ? "" : " + ") + s;
        std::fprintf(stderr, "%s %g, realisation %d: %s (%s), base reduced chi2 %.3g\n", cause.label.c_str(), size, r,
                     solver::ToString(result.verdict).c_str(), selected.c_str(), result.base.reduced_chi_square);
      }
      std::filesystem::remove_all(written.folder);
      const support::RateInterval rate = support::WilsonInterval(named, kRealisations);
      const std::string at = fmt::format("@{:g}{}", size, cause.label);
      state.counters["named" + at] = rate.rate;
      state.counters["low" + at] = rate.low;
      state.counters["high" + at] = rate.high;
    }
  }
}

void AddPointMass(nlohmann::json& scenario, double position_m, double mass_kg) {
  scenario["attachments"]["point_masses"] = {{{"position_m", position_m}, {"mass_kg", mass_kg}}};
}

nlohmann::json& Sensor(nlohmann::json& scenario, const std::string& channel) {
  for (nlohmann::json& sensor : scenario["sensors"])
    if (sensor["channel"] == channel) return sensor;
  throw std::invalid_argument("no sensor " + channel);
}

// Masses in grams. At the drive point or a sensor the mass is named as
// the instruments' (instrument_masses, a mass at each) or as one added mass;
// at 0.45 m, where no instrument sits (a cable clamp), as an added mass.
void MassAtDrive(nlohmann::json& s, double g) { AddPointMass(s, 0.57, 1e-3 * g); }
const Cause kMassAtDrive{"g", {1, 2, 4}, MassAtDrive, {"instrument_masses", "added_mass"}};
// Smaller masses for propagated σ.
const Cause kSmallMassAtDrive{"g", {0.25, 0.5, 1}, MassAtDrive, {"instrument_masses", "added_mass"}};
const Cause kMassAtSensor{"g", {1, 2, 4}, [](nlohmann::json& s, double g) { AddPointMass(s, 0.3, 1e-3 * g); },
                          {"instrument_masses", "added_mass"}};
const Cause kMassElsewhere{"g", {2, 4, 8}, [](nlohmann::json& s, double g) { AddPointMass(s, 0.45, 1e-3 * g); },
                           {"added_mass"}};
const Cause kSmallMassAtSensor{"g", {0.25, 0.5, 1}, kMassAtSensor.conceal, kMassAtSensor.names};
const Cause kSmallMassElsewhere{"g", {0.5, 1, 2}, kMassElsewhere.conceal, kMassElsewhere.names};
// The beam's modulus off its nominal value, in per cent.
void LowerModulus(nlohmann::json& s, double pct) {
  s["nominal_beam"] = {{"youngs_modulus_Pa", s["beam"]["youngs_modulus_Pa"]}};
  s["beam"]["youngs_modulus_Pa"] = s["beam"]["youngs_modulus_Pa"].get<double>() * (1.0 - 0.01 * pct);
}
const Cause kModulus{"pct", {0.05, 0.1, 0.2}, LowerModulus, {"modulus_error"}};
// Smaller changes for propagated σ.
const Cause kSmallModulus{"pct", {0.01, 0.02, 0.05}, LowerModulus, {"modulus_error"}};
// The clamp's rotational stiffness, in N·m/rad: smaller is more compliant.
const Cause kClamp{"Nm_rad",
                   {1e6, 3e5, 1e5},
                   [](nlohmann::json& s, double k) { s["attachments"]["clamp_rotational_stiffness_Nm_rad"] = k; },
                   {"clamp_compliance"}};
const Cause kStiffClamp{"Nm_rad", {1e7, 3e6, 1e6}, kClamp.conceal, kClamp.names};
// acc2's calibration off, in per cent.
void OffsetAcc2Gain(nlohmann::json& s, double pct) { Sensor(s, "acc2")["gain_error_relative"] = 0.01 * pct; }
const Cause kSensorGain{"pct", {0.02, 0.05, 0.1}, OffsetAcc2Gain, {"sensor_gain(acc2)"}};
// The same under propagated σ, whose test sees smaller errors.
const Cause kSensorGainSmall{"pct", {0.005, 0.01, 0.02, 0.05}, OffsetAcc2Gain, {"sensor_gain(acc2)"}};
// acc2 glued this far (mm) from where campaign.json says.
const Cause kSensorPosition{"mm",
                            {0.5, 1, 2},
                            [](nlohmann::json& s, double mm) {
                              nlohmann::json& acc2 = Sensor(s, "acc2");
                              acc2["stated_position_m"] = acc2["position_m"];
                              acc2["position_m"] = acc2["position_m"].get<double>() + 1e-3 * mm;
                            },
                            {"sensor_position(acc2)"}};
const Cause kSmallSensorPosition{"mm", {0.1, 0.2, 0.5}, kSensorPosition.conceal, kSensorPosition.names};
// The acquisition's clock off, in ppm (beyond the scenario's 25 ppm offset
// of the generator, which the model reads from the force).
const Cause kClock{"ppm",
                   {20, 50, 100},
                   [](nlohmann::json& s, double ppm) { s["timing"]["daq_clock_error_relative"] = 1e-6 * ppm; },
                   {"clock_error"}};
// Beyond 500 ppm, where clock_error is tried (below that a clock error is
// named as the modulus error it equals for the model).
const Cause kLargeClock{"ppm", {700, 1000, 2000}, kClock.conceal, {"clock_error"}};

// A Jenkins element (stiffness 50 N·m/rad beside k1 = 100, so 150 while it
// sticks, as the paper's support) slipping at this moment (N·m). Its effect
// is not monotonic in the moment: one that never slips over the measured
// rotations is a linear spring, one that slips at once a weak damper; the
// rates show the band of moments the diagnosis names.
const Cause kFriction{"Nm",
                      {0.02, 0.05, 0.15, 0.4},
                      [](nlohmann::json& s, double moment) { support::AddSupportFriction(s, 100.0, 50.0, moment); },
                      {"support_friction"}};
// Smaller moments: a slider that slips at once, a Coulomb damper.
const Cause kSmallFriction{"Nm", {1e-4, 1e-3, 1e-2}, kFriction.conceal, {"support_friction"}};

BENCHMARK_CAPTURE(BM_DetectionPower, mass_at_drive, kMassAtDrive)->Iterations(1)->Unit(benchmark::kSecond);
BENCHMARK_CAPTURE(BM_DetectionPower, mass_at_drive_propagated, kSmallMassAtDrive, solver::PhasorUncertainty::kPropagated)
    ->Iterations(1)->Unit(benchmark::kSecond);
BENCHMARK_CAPTURE(BM_DetectionPower, mass_at_sensor, kMassAtSensor)->Iterations(1)->Unit(benchmark::kSecond);
BENCHMARK_CAPTURE(BM_DetectionPower, mass_at_sensor_propagated, kSmallMassAtSensor, solver::PhasorUncertainty::kPropagated)
    ->Iterations(1)->Unit(benchmark::kSecond);
BENCHMARK_CAPTURE(BM_DetectionPower, mass_elsewhere, kMassElsewhere)->Iterations(1)->Unit(benchmark::kSecond);
BENCHMARK_CAPTURE(BM_DetectionPower, mass_elsewhere_propagated, kSmallMassElsewhere, solver::PhasorUncertainty::kPropagated)
    ->Iterations(1)->Unit(benchmark::kSecond);
BENCHMARK_CAPTURE(BM_DetectionPower, modulus, kModulus)->Iterations(1)->Unit(benchmark::kSecond);
BENCHMARK_CAPTURE(BM_DetectionPower, modulus_propagated, kSmallModulus, solver::PhasorUncertainty::kPropagated)
    ->Iterations(1)->Unit(benchmark::kSecond);
BENCHMARK_CAPTURE(BM_DetectionPower, clamp, kClamp)->Iterations(1)->Unit(benchmark::kSecond);
BENCHMARK_CAPTURE(BM_DetectionPower, clamp_propagated, kStiffClamp, solver::PhasorUncertainty::kPropagated)
    ->Iterations(1)->Unit(benchmark::kSecond);
BENCHMARK_CAPTURE(BM_DetectionPower, sensor_gain, kSensorGain)->Iterations(1)->Unit(benchmark::kSecond);
BENCHMARK_CAPTURE(BM_DetectionPower, sensor_gain_propagated, kSensorGainSmall, solver::PhasorUncertainty::kPropagated)
    ->Iterations(1)->Unit(benchmark::kSecond);
BENCHMARK_CAPTURE(BM_DetectionPower, sensor_position, kSensorPosition)->Iterations(1)->Unit(benchmark::kSecond);
BENCHMARK_CAPTURE(BM_DetectionPower, sensor_position_propagated, kSmallSensorPosition, solver::PhasorUncertainty::kPropagated)
    ->Iterations(1)->Unit(benchmark::kSecond);
BENCHMARK_CAPTURE(BM_DetectionPower, clock, kClock)->Iterations(1)->Unit(benchmark::kSecond);
BENCHMARK_CAPTURE(BM_DetectionPower, clock_propagated, kLargeClock, solver::PhasorUncertainty::kPropagated)
    ->Iterations(1)->Unit(benchmark::kSecond);
BENCHMARK_CAPTURE(BM_DetectionPower, friction, kFriction)->Iterations(1)->Unit(benchmark::kSecond);
BENCHMARK_CAPTURE(BM_DetectionPower, friction_propagated, kFriction, solver::PhasorUncertainty::kPropagated)
    ->Iterations(1)->Unit(benchmark::kSecond);
BENCHMARK_CAPTURE(BM_DetectionPower, small_friction_propagated, kSmallFriction,
                  solver::PhasorUncertainty::kPropagated)
    ->Iterations(1)->Unit(benchmark::kSecond);

}  // namespace
