// A report's input and curves with everything the page draws, for the
// report's layout tests: three levels of a hardening response on a fitted
// and a held-out channel (a model curve that folds at the top level, phase,
// harmonics 2 and 3, a flagged step), backbone, damping points, a held-out
// time history and a residual map. Shapes, not physics: the plots' layout
// is what is tested with it.
#pragma once

#include <cmath>
#include <numbers>
#include <string>

#include "solver/report/report_curves.h"
#include "solver/report/report_input.h"

namespace beamid::testing {

inline solver::ReportInput SampleReportInput() {
  using namespace solver;
  ReportInput input;
  input.result_file = "out/result.json";
  input.campaign_folder = "campaign";
  input.result.model.fit_channels = {"acc1", "acc2"};
  input.result.parameters = {{.name = "k1", .unit = "N*m/rad", .value = 150.0, .std = 0.002}};
  return input;
}

// Three levels of a hardening response on two channels: a model curve that
// folds (an unstable branch) at the top level, measured steps with a phase
// and harmonics 2 and 3, a flagged step, the backbone, the damping points,
// a held-out time history and a residual map: everything the page draws.
inline solver::ReportCurves SampleReportCurves() {
  using namespace solver;
  ReportCurves curves;
  curves.channels = {{.channel = "acc1", .position_m = 0.1, .si_unit = "m/s^2", .fitted = true},
                     {.channel = "acc3", .position_m = 0.57, .si_unit = "m/s^2", .fitted = false}};
  const double forces[] = {1.0, 4.0, 9.0};
  const char* names[] = {"low", "mid", "high"};
  for (int l = 0; l < 3; ++l) {
    LevelCurves level{.level = names[l], .force_amplitude_N = forces[l]};
    const double shift = 0.3 * l;  // the resonance rises with the level
    auto response = [&](double f) { return forces[l] * 8.0 / std::hypot(1.0, (f - 54.0 - shift) / 0.3); };
    auto phase = [&](double f) { return -90.0 - 180.0 / std::numbers::pi * std::atan((f - 54.0 - shift) / 0.3); };
    for (double f = 50.0; f <= 58.0; f += 0.25)
      level.measured.push_back(
          {.frequency_hz = f,
           .amplitude = {response(f), 0.6 * response(f)},
           .file = std::string(names[l]) + std::to_string(f),
           .force_amplitude_N = forces[l],
           .phase_deg = {phase(f), phase(f)},
           .higher_harmonics = {{1e-4 * forces[l], 2e-3 * forces[l] * forces[l]}, {1e-4, 1e-3 * forces[l]}}});
    for (double f = 49.9; f <= 58.1; f += 0.05)
      level.model.push_back({.frequency_hz = f,
                             .amplitude = {response(f), 0.6 * response(f)},
                             .stable = !(l == 2 && f > 54.5 && f < 54.9),
                             .phase_deg = {phase(f), phase(f)},
                             .higher_harmonics = {{1e-5, 2e-3 * forces[l] * forces[l]}, {1e-5, 1e-3}}});
    curves.levels.push_back(level);
  }
  curves.levels[1].measured[10].flag = "recorded before it settled";
  for (double f = 54.0; f <= 55.0; f += 0.05)
    curves.backbone.push_back({.frequency_hz = f, .amplitude = 60.0 * (f - 53.9)});
  curves.phase_resonance = {{.level = "low",
                             .frequency_hz = 54.0,
                             .frequency_std_hz = 0.001,
                             .amplitude = 8.0,
                             .amplitude_std = 0.01,
                             .model_frequency_hz = 54.0}};
  curves.measured_mode.damping = {{.level = "low", .amplitude = 8.0, .quadrature = 0.006, .quadrature_std = 1e-4},
                                  {.level = "high", .amplitude = 72.0, .quadrature = 0.005, .quadrature_std = 1e-4}};
  curves.held_out_channel = "acc3";
  TimeHistory history{.level = "high", .frequency_hz = 54.8};
  for (int n = 0; n < 96; ++n) {
    const double t = n / 96.0 / 54.8;
    history.time_s.push_back(t);
    history.predicted.push_back(40 * std::sin(2 * std::numbers::pi * 54.8 * t));
    history.predicted_std.push_back(0.5);
    history.measured.push_back(40.2 * std::sin(2 * std::numbers::pi * 54.8 * t));
  }
  curves.time_histories = {history};
  curves.residuals.rows = {"acc1 h1"};
  curves.residuals.step_level = {"low", "low", "high"};
  curves.residuals.step_frequency_hz = {54.0, 54.5, 54.8};
  curves.residuals.whitened_norm = Eigen::MatrixXd::Constant(1, 3, 0.5);
  return curves;
}

// A residual map of ones (1 σ everywhere) over the level's measured steps,
// one row (acc1 h1): what the pages need to draw one.
inline solver::ResidualMap UnitResidualMap(const solver::LevelCurves& level) {
  solver::ResidualMap map;
  map.rows = {"acc1 h1"};
  for (const auto& m : level.measured) {
    map.step_level.push_back(level.level);
    map.step_frequency_hz.push_back(m.frequency_hz);
  }
  map.whitened_norm = Eigen::MatrixXd::Ones(1, static_cast<Eigen::Index>(level.measured.size()));
  return map;
}

// One fitted channel at one level (three steps), the model's curve and
// backbone, two damping points (none: the damping trend not judged) with the
// measured backbone's verdict `trend` at `z`, and a residual map of ones: the
// least a page needs for its captions and verdicts to be tested.
inline solver::ReportCurves MinimalReportCurves(solver::Trend trend, double z, bool damping = true) {
  using namespace solver;
  ReportCurves curves;
  curves.channels = {{.channel = "acc1", .position_m = 0.1, .si_unit = "m/s^2", .fitted = true}};
  LevelCurves level{.level = "high", .force_amplitude_N = 9.0};
  for (double f : {54.5, 55.0, 55.5}) level.measured.push_back({.frequency_hz = f, .amplitude = {10.0 + f - 54.0}});
  for (double f = 54.0; f <= 56.0; f += 0.5) level.model.push_back({.frequency_hz = f, .amplitude = {12.0}});
  curves.levels = {level};
  for (double f = 54.0; f <= 56.0; f += 0.5) curves.backbone.push_back({.frequency_hz = f, .amplitude = 5.0 + f - 54.0});
  if (damping)
    curves.measured_mode.damping = {{.level = "low", .amplitude = 1.0, .quadrature = 0.006, .quadrature_std = 1e-4},
                                    {.level = "high", .amplitude = 9.0, .quadrature = 0.011, .quadrature_std = 1e-4}};
  curves.measured_mode.damping_rate_trend = trend;
  curves.measured_mode.damping_rate_trend_z = z;
  curves.residuals = UnitResidualMap(level);
  return curves;
}

}  // namespace beamid::testing
