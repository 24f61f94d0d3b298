#include "solver/diagnosis/measurement_suggestion.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <fmt/core.h>

#include "hb/option_checks.h"

namespace beamid::solver {
namespace {

// The noise of a channel at one step and harmonic as a real chain has it: a
// floor plus a part proportional to the channel's signal (its rms, i.e. its
// fundamental), σ_k = a_k + b_k·|Y_1|, a_k, b_k ≥ 0 fitted to the fitted
// channels' stated σ at that step (least squares; one channel: the floor).
struct NoiseModel {
  Eigen::VectorXd floor, per_amplitude;  // [k-1]
};

NoiseModel FitNoiseModel(const FitStep& step) {
  const Eigen::Index channels = step.std_amplitude.rows(), K = step.std_amplitude.cols();
  NoiseModel m{Eigen::VectorXd::Zero(K), Eigen::VectorXd::Zero(K)};
  const Eigen::VectorXd amplitude = step.measured.col(0).cwiseAbs();
  for (Eigen::Index k = 0; k < K; ++k) {
    const Eigen::VectorXd sigma = step.std_amplitude.col(k);
    m.floor(k) = sigma.minCoeff();
    if (channels < 2) continue;
    const double mean_a = amplitude.mean(), mean_s = sigma.mean();
    const double var_a = (amplitude.array() - mean_a).square().sum();
    if (!(var_a > 0.0)) continue;
    const double slope = ((amplitude.array() - mean_a) * (sigma.array() - mean_s)).sum() / var_a;
    if (slope <= 0.0) continue;  // no signal-proportional part seen: the floor alone
    const double intercept = mean_s - slope * mean_a;
    if (intercept >= 0.0) {
      m.floor(k) = intercept;
      m.per_amplitude(k) = slope;
    } else {  // through the origin
      m.floor(k) = 0.0;
      m.per_amplitude(k) = amplitude.dot(sigma) / amplitude.squaredNorm();
    }
  }
  return m;
}

// Per step, Σ_k |ΔY_k|²/σ_k² of each channel of `probe`, σ from the noise
// models at the mean of the two models' fundamentals there.
std::vector<Eigen::VectorXd> StepGains(const FitData& probe, const FittedModel& a, const FittedModel& b,
                                       const std::vector<NoiseModel>& noise) {
  const auto ya = a.Phasors(probe);
  const auto yb = b.Phasors(probe);
  std::vector<Eigen::VectorXd> gains;
  for (std::size_t i = 0; i < probe.steps.size(); ++i) {
    Eigen::VectorXd g = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(probe.channels.size()));
    for (Eigen::Index c = 0; c < g.size(); ++c) {
      const double amplitude = 0.5 * (std::abs(ya[i](c, 0)) + std::abs(yb[i](c, 0)));
      for (int k = 0; k < probe.num_fit_harmonics; ++k) {
        const double sigma = noise[i].floor(k) + noise[i].per_amplitude(k) * amplitude;
        g(c) += std::norm(ya[i](c, k) - yb[i](c, k)) / (sigma * sigma);
      }
    }
    gains.push_back(g);
  }
  return gains;
}

}  // namespace

void SuggestionOptions::Validate() const {
  option_checks::RequireInRange("SuggestionOptions.num_positions", num_positions, 1, 1000);
}

MeasurementSuggestion SuggestMeasurement(const FitData& fit, const FittedModel& a, const std::string& a_name,
                                         const FittedModel& b, const std::string& b_name,
                                         const SuggestionOptions& options) {
  options.Validate();
  MeasurementSuggestion s{.first = a_name, .second = b_name};
  const std::size_t num_steps = fit.steps.size();

  std::vector<NoiseModel> noise;
  for (const FitStep& step : fit.steps) noise.push_back(FitNoiseModel(step));
  for (const auto& g : StepGains(fit, a, b, noise)) s.current_expected += g.sum();

  FitData probe = fit;
  probe.channels.clear();
  const int derivative = fit.channels.empty() ? 2 : fit.channels.front().derivative_order;
  for (int i = 1; i <= options.num_positions; ++i)
    probe.channels.push_back({.channel = "probe",
                              .position_m = fit.beam.length_m * i / (options.num_positions + 1.0),
                              .derivative_order = derivative});
  const std::vector<Eigen::VectorXd> gains = StepGains(probe, a, b, noise);
  Eigen::Index best = 0;
  for (Eigen::Index c = 0; c < static_cast<Eigen::Index>(probe.channels.size()); ++c) {
    double total = 0.0;
    for (const auto& g : gains) total += g(c);
    s.positions.push_back({.position_m = probe.channels[c].position_m, .expected_chi_square_difference = total});
    if (total > s.positions[best].expected_chi_square_difference) best = c;
  }
  s.best = s.positions[best];

  // Where the best position's difference lies: per level, and the narrowest
  // frequency band holding 80 % of it.
  for (const std::string& level : fit.levels) {
    double sum = 0.0;
    for (std::size_t i = 0; i < num_steps; ++i)
      if (fit.steps[i].level == level) sum += gains[i](best);
    s.levels.push_back({.level = level, .share = sum / std::max(s.best.expected_chi_square_difference, 1e-300)});
  }
  std::vector<std::size_t> order(num_steps);
  for (std::size_t i = 0; i < num_steps; ++i) order[i] = i;
  std::sort(order.begin(), order.end(),
            [&](std::size_t x, std::size_t y) { return fit.steps[x].omega_rad_s < fit.steps[y].omega_rad_s; });
  double width = 1e300;
  for (std::size_t lo = 0; lo < num_steps; ++lo) {
    double sum = 0.0;
    for (std::size_t hi = lo; hi < num_steps; ++hi) {
      sum += gains[order[hi]](best);
      if (sum >= 0.8 * s.best.expected_chi_square_difference) {
        const double f_lo = fit.steps[order[lo]].omega_rad_s / (2 * std::numbers::pi);
        const double f_hi = fit.steps[order[hi]].omega_rad_s / (2 * std::numbers::pi);
        if (f_hi - f_lo < width) {
          width = f_hi - f_lo;
          s.focus_low_hz = f_lo;
          s.focus_high_hz = f_hi;
        }
        break;
      }
    }
  }
  const auto top_level = std::max_element(s.levels.begin(), s.levels.end(),
                                          [](const LevelShare& x, const LevelShare& y) { return x.share < y.share; });
  s.text = fmt::format(
      "To tell {} from {}: add an accelerometer at x = {:.3f} m, where the two refits differ by an expected "
      "chi-square of {:.3g} over these steps (the fitted channels give {:.3g}; above {:.3g} decides at 99 %){}; "
      "{:.0f} % of it lies at level {}, and 80 % between {:.2f} and {:.2f} Hz: step finely there.",
      a_name, b_name, s.best.position_m, s.best.expected_chi_square_difference, s.current_expected, kDecisiveChiSquare,
      s.best.expected_chi_square_difference > kDecisiveChiSquare ? "" : " — not enough alone: record longer or more steps",
      top_level == s.levels.end() ? 0.0 : 100.0 * top_level->share,
      top_level == s.levels.end() ? std::string("-") : top_level->level, s.focus_low_hz, s.focus_high_hz);
  return s;
}

}  // namespace beamid::solver
