#include "solver/live/next_step_planner.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <memory>
#include <numbers>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <fmt/format.h>

#include "hb/errors.h"
#include "hb/linear_beam.h"
#include "hb/option_checks.h"
#include "solver/estimation/fit_problem.h"

namespace beamid::solver {

void PlannerOptions::Validate() const {
  using option_checks::RequireInRange;
  if (levels.empty()) throw InputError("levels: none given. Fix: give at least one force level (LABEL=FORCE_N)");
  for (const PlanLevel& level : levels) {
    if (level.label.empty()) throw InputError("levels: a level without a label. Fix: give LABEL=FORCE_N");
    RequireInRange("force of level " + level.label + " [N]", level.force_N, 1e-9, 1e6);
  }
  RequireInRange("--band LOW", band_low_hz, 1e-3, 1e6);
  RequireInRange("--band HIGH", band_high_hz, band_low_hz, 1e6);
  RequireInRange("--resolution", resolution_hz, 1e-6, band_high_hz - band_low_hz + 1.0);
  RequireInRange("--max-step", max_step_hz, resolution_hz, 1e6);
  if (targets.empty()) throw InputError("targets: none given. Fix: name at least one parameter (k1, k3, c, ...)");
  for (const auto& [name, std] : target_std) RequireInRange("target σ of " + name, std, 0.0, 1e300);
  RequireInRange("--target-relative", target_relative_std, 1e-9, 10.0);
  RequireInRange("min_gain", min_gain, 0.0, 100.0);
  RequireInRange("--max-steps", max_steps, 1, 100000);
  RequireInRange("--settle-tolerance", settle_tolerance, 1e-12, 0.5);
  RequireInRange("--max-record", max_record_s, 1e-3, 3600.0);
  RequireInRange("min_settle_s", min_settle_s, 0.0, 3600.0);
  RequireInRange("max_settle_s", max_settle_s, min_settle_s, 3600.0);
}

LinearResonance FirstResonance(const FitData& data, const ModelStructure& structure) {
  hb::LinearBeamModel model = structure.ApplyLinear({.beam = data.beam, .attachments = data.sensor_masses});
  const std::vector<std::string> names = structure.Names();
  const std::vector<double> values = structure.Values();
  for (std::size_t i = 0; i < names.size(); ++i) {
    if (names[i] == "k1") model.support_stiffness_Nm_rad = values[i];
    if (names[i] == "c") model.support_damping_Nms_rad = values[i];
  }
  const hb::LinearBeam beam(model, data.force_position_m);
  const double omega_1 = beam.NaturalFrequencies_rad_s(1).at(0);
  constexpr int kPoints = 801;
  std::vector<double> omega(kPoints), amplitude(kPoints);
  int peak = 0;
  for (int i = 0; i < kPoints; ++i) {
    omega[i] = omega_1 * (0.9 + 0.2 * i / (kPoints - 1));
    amplitude[i] = std::abs(beam.RespondToForce(omega[i]).Displacement_m(data.force_position_m));
    if (amplitude[i] > amplitude[peak]) peak = i;
  }
  const double half = amplitude[peak] / std::numbers::sqrt2;
  int low = peak, high = peak;
  while (low > 0 && amplitude[low] > half) --low;
  while (high < kPoints - 1 && amplitude[high] > half) ++high;
  if (amplitude[low] > half || amplitude[high] > half) return {};
  // Linear interpolation to the half-power crossings.
  const auto crossing = [&](int outside, int inside) {
    return omega[outside] +
           (omega[inside] - omega[outside]) * (half - amplitude[outside]) / (amplitude[inside] - amplitude[outside]);
  };
  return {.frequency_hz = omega[peak] / (2.0 * std::numbers::pi),
          .decay_rate_per_s = 0.5 * (crossing(high, high - 1) - crossing(low, low + 1))};
}

namespace {

std::vector<int> TargetIndices(const ModelStructure& structure, const PlannerOptions& options) {
  const std::vector<std::string> names = structure.Names();
  std::vector<int> out;
  for (const std::string& target : options.targets) {
    const auto it = std::find(names.begin(), names.end(), target);
    if (it == names.end())
      throw InputError("target parameter \"" + target + "\" is no parameter of the model. Fix: name one of " +
                           fmt::format("{}", fmt::join(names, ", ")));
    out.push_back(static_cast<int>(it - names.begin()));
  }
  return out;
}

// σ²·T = a² + b²·|Y₁|² per channel and harmonic, fitted (least squares,
// a², b² ≥ 0) to the steps measured so far: the noise floor and the part
// proportional to the response, each falling as 1/√T.
struct NoiseModel {
  Eigen::MatrixXd floor_sq;         // channels × K: a²
  Eigen::MatrixXd proportional_sq;  // channels × K: b²
  double Std(int c, int k, double fundamental, double record_s) const {
    return std::sqrt((floor_sq(c, k) + proportional_sq(c, k) * fundamental * fundamental) / record_s);
  }
};

NoiseModel FitNoise(const FitData& data, const std::vector<double>& analysed_s) {
  const int channels = static_cast<int>(data.channels.size());
  const int k_max = data.num_fit_harmonics;
  NoiseModel noise{Eigen::MatrixXd::Zero(channels, k_max), Eigen::MatrixXd::Zero(channels, k_max)};
  const int n = static_cast<int>(data.steps.size());
  for (int c = 0; c < channels; ++c)
    for (int k = 0; k < k_max; ++k) {
      Eigen::MatrixXd a(n, 2);
      Eigen::VectorXd y(n);
      for (int i = 0; i < n; ++i) {
        const FitStep& s = data.steps[static_cast<std::size_t>(i)];
        const double t = analysed_s.size() == data.steps.size() ? analysed_s[static_cast<std::size_t>(i)] : 1.0;
        const double amplitude = std::abs(s.measured(c, 0));
        a(i, 0) = 1.0;
        a(i, 1) = amplitude * amplitude;
        y(i) = s.std_amplitude(c, k) * s.std_amplitude(c, k) * t;
      }
      Eigen::Vector2d coefficients = Eigen::Vector2d::Zero();
      if (n >= 2) coefficients = a.colPivHouseholderQr().solve(y);
      if (n < 2 || coefficients(0) < 0.0 || coefficients(1) < 0.0) {
        // One term alone: whichever explains the scatter better.
        const double floor_only = y.mean();
        const double proportional_only = a.col(1).squaredNorm() > 0.0 ? a.col(1).dot(y) / a.col(1).squaredNorm() : 0.0;
        const double floor_misfit = (y.array() - floor_only).matrix().squaredNorm();
        const double proportional_misfit = (y - proportional_only * a.col(1)).squaredNorm();
        coefficients = floor_misfit <= proportional_misfit ? Eigen::Vector2d(floor_only, 0.0)
                                                           : Eigen::Vector2d(0.0, proportional_only);
      }
      noise.floor_sq(c, k) = std::max(coefficients(0), 0.0);
      noise.proportional_sq(c, k) = std::max(coefficients(1), 0.0);
    }
  return noise;
}

// A symmetric positive semi-definite matrix's inverse, its eigenvalues
// below 1e-12 of the largest raised to that (an unidentified direction
// keeps a huge but finite variance).
Eigen::MatrixXd RegularisedInverse(const Eigen::MatrixXd& m) {
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(m);
  Eigen::VectorXd values = eigen.eigenvalues();
  const double floor = std::max(values.maxCoeff(), 1e-300) * 1e-12;
  for (Eigen::Index i = 0; i < values.size(); ++i) values(i) = 1.0 / std::max(values(i), floor);
  return eigen.eigenvectors() * values.asDiagonal() * eigen.eigenvectors().transpose();
}

double LogDet(const Eigen::MatrixXd& m) {
  const Eigen::LDLT<Eigen::MatrixXd> ldlt(m);
  return ldlt.vectorD().array().max(1e-300).log().sum();
}

Eigen::MatrixXd Block(const Eigen::MatrixXd& m, const std::vector<int>& indices) {
  Eigen::MatrixXd out(indices.size(), indices.size());
  for (std::size_t i = 0; i < indices.size(); ++i)
    for (std::size_t j = 0; j < indices.size(); ++j) out(i, j) = m(indices[i], indices[j]);
  return out;
}

// Steps to predict, without measurements: the data's beam, sensors and
// channels, unit whitening (the residuals are the predicted phasors).
FitData CandidateData(const FitData& data) {
  FitData candidates;
  candidates.beam = data.beam;
  candidates.force_position_m = data.force_position_m;
  candidates.sensor_masses = data.sensor_masses;
  candidates.channels = data.channels;
  candidates.num_fit_harmonics = data.num_fit_harmonics;
  candidates.uncertainty = PhasorUncertainty::kRelativeFloor;
  return candidates;
}

void AddCandidate(FitData& candidates, const PlanLevel& level, double frequency_hz, int num_harmonics) {
  const int channels = static_cast<int>(candidates.channels.size());
  const int k_max = candidates.num_fit_harmonics;
  FitStep step;
  step.level = level.label;
  step.omega_rad_s = 2.0 * std::numbers::pi * frequency_hz;
  step.nominal_frequency_hz = frequency_hz;
  step.force_N = Eigen::VectorXcd::Zero(num_harmonics + 1);
  step.force_N(1) = level.force_N;
  step.measured = Eigen::MatrixXcd::Zero(channels, k_max);
  step.whitening.assign(static_cast<std::size_t>(channels),
                        std::vector<Eigen::Matrix2d>(static_cast<std::size_t>(k_max), Eigen::Matrix2d::Identity()));
  step.std_amplitude = Eigen::MatrixXd::Ones(channels, k_max);
  if (std::find(candidates.levels.begin(), candidates.levels.end(), level.label) == candidates.levels.end())
    candidates.levels.push_back(level.label);
  candidates.steps.push_back(std::move(step));
}

}  // namespace

SweepChoice ChooseSweepDirection(const PlannerFit& fit, const PlanLevel& level, const PlannerOptions& options) {
  SweepChoice choice;
  const LinearResonance resonance = FirstResonance(*fit.data, *fit.structure);
  if (!(resonance.decay_rate_per_s > 0.0)) return choice;
  choice.linear_peak_hz = resonance.frequency_hz;
  choice.half_width_hz = resonance.decay_rate_per_s / (2.0 * std::numbers::pi);
  FitData band = CandidateData(*fit.data);
  const double tolerance_hz = 1e-6 * options.resolution_hz;
  for (int m = 0; options.band_low_hz + m * options.resolution_hz <= options.band_high_hz + tolerance_hz; ++m)
    AddCandidate(band, level, options.band_low_hz + m * options.resolution_hz, fit.model.num_harmonics);
  const std::unique_ptr<FitProblem> problem = fit.family->MakeProblem(band, *fit.structure, fit.model);
  const Eigen::VectorXd predicted = problem->WeightedResiduals(problem->FeasiblePoint(fit.structure->Values()));
  // Every sensor's first harmonic, each relative to its largest: the peak of the mode they share.
  const int channels = static_cast<int>(band.channels.size());
  const int k_max = band.num_fit_harmonics;
  const int n = static_cast<int>(band.steps.size());
  Eigen::MatrixXd amplitude(n, channels);
  for (int i = 0; i < n; ++i)
    for (int c = 0; c < channels; ++c) amplitude(i, c) = predicted.segment<2>(2 * (i * channels + c) * k_max).norm();
  if (!amplitude.allFinite()) return choice;
  Eigen::VectorXd score = Eigen::VectorXd::Zero(n);
  for (int c = 0; c < channels; ++c)
    if (amplitude.col(c).maxCoeff() > 0.0) score += amplitude.col(c) / amplitude.col(c).maxCoeff();
  Eigen::Index peak = 0;
  score.maxCoeff(&peak);
  choice.peak_hz = band.steps[static_cast<std::size_t>(peak)].nominal_frequency_hz;
  if (choice.peak_hz < choice.linear_peak_hz - choice.half_width_hz) choice.direction = SweepDirection::kDown;
  return choice;
}

std::vector<PlanParameter> TargetStatus(const ModelStructure& structure, const Eigen::MatrixXd& covariance,
                                        const PlannerOptions& options) {
  const std::vector<std::string> names = structure.Names();
  const std::vector<std::string> units = structure.Units();
  const std::vector<double> values = structure.Values();
  std::vector<PlanParameter> out;
  for (std::size_t i = 0; i < names.size(); ++i) {
    PlanParameter p{.name = names[i], .unit = units[i], .value = values[i]};
    const auto row = static_cast<Eigen::Index>(i);
    p.std = row < covariance.rows() ? std::sqrt(std::max(covariance(row, row), 0.0)) : 0.0;
    p.lower_95 = p.value - 1.96 * p.std;
    p.upper_95 = p.value + 1.96 * p.std;
    if (std::find(options.targets.begin(), options.targets.end(), names[i]) != options.targets.end()) {
      const auto it = options.target_std.find(names[i]);
      p.target_std = it != options.target_std.end() ? it->second : options.target_relative_std * std::abs(values[i]);
    }
    out.push_back(p);
  }
  return out;
}

CandidateChoice ChooseNextStep(const PlannerFit& fit, const std::map<std::string, LevelSweep>& swept, int last_step,
                               const PlannerOptions& options, double min_record_s, double extra_settle_s,
                               const std::optional<PlanFocus>& focus) {
  options.Validate();
  const FitData& data = *fit.data;
  const ModelStructure& structure = *fit.structure;
  const std::vector<int> targets = TargetIndices(structure, options);
  CandidateChoice choice;

  // The candidates: on each level, the grid ahead of its last step.
  FitData candidates = CandidateData(data);
  const int channels = static_cast<int>(data.channels.size());
  const int k_max = data.num_fit_harmonics;
  std::vector<double> candidate_force;
  std::vector<SweepDirection> candidate_sweep;
  std::map<std::string, std::string> sweep_why;  // a level begun downwards: why
  const double tolerance_hz = 1e-6 * options.resolution_hz;
  const LinearResonance resonance = FirstResonance(data, structure);
  if (!(resonance.decay_rate_per_s > 0.0)) {
    choice.why_none = "the fitted model has no resonance peak to time the settling by (its first mode is not damped "
                      "within ±10 % of its frequency)";
    return choice;
  }
  for (const PlanLevel& level : options.levels) {
    std::vector<double> frequencies;
    const auto begun = swept.find(level.label);
    SweepDirection direction = begun != swept.end() ? begun->second.direction : SweepDirection::kUp;
    if (focus) {
      if (level.label != focus->level) continue;
      for (double f = focus->low_hz; f <= focus->high_hz + tolerance_hz; f += options.resolution_hz) {
        const bool measured = std::any_of(data.steps.begin(), data.steps.end(), [&](const FitStep& step) {
          return step.level == level.label && std::abs(step.nominal_frequency_hz - f) < 0.5 * options.resolution_hz;
        });
        if (!measured) frequencies.push_back(f);
      }
    } else if (begun == swept.end()) {
      const SweepChoice sweep = fit.within_noise ? ChooseSweepDirection(fit, level, options) : SweepChoice{};
      direction = sweep.direction;
      if (direction == SweepDirection::kDown) {
        sweep_why[level.label] = fmt::format(
            "sweeping {} downwards: the fitted support softens, its response there peaks at {:.2f} Hz, below the "
            "linear resonance at {:.2f} Hz; ",
            level.label, sweep.peak_hz, sweep.linear_peak_hz);
        const double bottom = std::max(options.band_low_hz, resonance.frequency_hz);
        for (int m = 0; options.band_high_hz - m * options.resolution_hz >= bottom - tolerance_hz; ++m)
          frequencies.push_back(options.band_high_hz - m * options.resolution_hz);
        if (frequencies.empty()) frequencies.push_back(options.band_high_hz);
      } else {
        const double top = std::min(options.band_high_hz, resonance.frequency_hz);
        for (int m = 0; options.band_low_hz + m * options.resolution_hz <= top + tolerance_hz; ++m)
          frequencies.push_back(options.band_low_hz + m * options.resolution_hz);
        if (frequencies.empty()) frequencies.push_back(options.band_low_hz);
      }
    } else {
      const double sign = direction == SweepDirection::kDown ? -1.0 : 1.0;
      for (int m = 1;; ++m) {
        const double f = begun->second.last_hz + sign * m * options.resolution_hz;
        if (f > options.band_high_hz + tolerance_hz || f < options.band_low_hz - tolerance_hz ||
            m * options.resolution_hz > options.max_step_hz + tolerance_hz)
          break;
        frequencies.push_back(f);
      }
    }
    for (const double f : frequencies) {
      AddCandidate(candidates, level, f, fit.model.num_harmonics);
      candidate_force.push_back(level.force_N);
      candidate_sweep.push_back(direction);
    }
  }
  choice.candidates = static_cast<int>(candidates.steps.size());
  if (candidates.steps.empty()) {
    choice.why_none = focus ? "every step where the competing causes differ has been measured"
                            : "every level has been swept through the band";
    return choice;
  }

  // Unit whitening: the residuals are the predicted phasors themselves and
  // the Jacobian their sensitivities, rescaled below by each phasor's σ.
  const std::unique_ptr<FitProblem> problem = fit.family->MakeProblem(candidates, structure, fit.model);
  const Eigen::VectorXd x = problem->FeasiblePoint(structure.Values());
  const Eigen::VectorXd predicted = problem->WeightedResiduals(x);
  Eigen::MatrixXd jacobian = problem->ReducedResidualJacobian(x);
  const NoiseModel noise = FitNoise(data, fit.analysed_s);

  // Scale-free: parameters in units of their present σ.
  const int p = static_cast<int>(fit.covariance.rows());
  Eigen::VectorXd scale = fit.covariance.diagonal().cwiseMax(0.0).cwiseSqrt();
  for (int i = 0; i < p; ++i)
    if (!(scale(i) > 0.0) || !std::isfinite(scale(i))) scale(i) = 1.0;
  const Eigen::MatrixXd covariance =
      scale.cwiseInverse().asDiagonal() * fit.covariance * scale.cwiseInverse().asDiagonal();
  const Eigen::MatrixXd information = RegularisedInverse(covariance);
  const double log_det_now = LogDet(Block(covariance, targets));

  const double decay_per_s = resonance.decay_rate_per_s;
  const FitStep& now = data.steps.at(static_cast<std::size_t>(last_step));
  const int rows_per_step = 2 * channels * k_max;
  double best_per_s = -1.0;
  for (int i = 0; i < choice.candidates; ++i) {
    double change = 0.0;
    for (int c = 0; c < channels; ++c) {
      const Eigen::Vector2d y = predicted.segment<2>(2 * (c * k_max) + i * rows_per_step);
      const std::complex<double> y_now = now.measured(c, 0);
      change = std::max(change, std::hypot(y(0) - y_now.real(), y(1) - y_now.imag()) / y.norm());
    }
    const double settle_s =
        std::clamp(std::log(std::max(std::numbers::e, change / options.settle_tolerance)) / decay_per_s,
                   options.min_settle_s, options.max_settle_s) + extra_settle_s;
    // Whitened for a record of 1 s; a record of T s scales it by √T.
    Eigen::MatrixXd j = jacobian.middleRows(i * rows_per_step, rows_per_step) * scale.asDiagonal();
    for (int c = 0; c < channels; ++c) {
      const double fundamental = predicted.segment<2>(2 * (c * k_max) + i * rows_per_step).norm();
      for (int k = 0; k < k_max; ++k) j.middleRows(2 * (c * k_max + k), 2) /= noise.Std(c, k, fundamental, 1.0);
    }
    if (!j.allFinite()) continue;
    const Eigen::MatrixXd information_per_s = j.transpose() * j;
    // The record too is chosen for the gain per second: near resonance,
    // where a step must settle for seconds, recording a few seconds more
    // costs little and teaches in proportion.
    for (double record = min_record_s;; record = std::min(2.0 * record, options.max_record_s)) {
      const Eigen::MatrixXd after = RegularisedInverse(information + record * information_per_s);
      const double gain = log_det_now - LogDet(Block(after, targets));
      const double per_s = gain / (settle_s + record);
      if (per_s > best_per_s) {
        best_per_s = per_s;
        const FitStep& s = candidates.steps[static_cast<std::size_t>(i)];
        choice.step = PlannedStep{.level = s.level,
                                  .force_N = candidate_force[static_cast<std::size_t>(i)],
                                  .frequency_hz = s.nominal_frequency_hz,
                                  .settle_s = settle_s,
                                  .record_s = record,
                                  .expected_gain = gain,
                                  .expected_gain_per_s = per_s,
                                  .sweep = candidate_sweep[static_cast<std::size_t>(i)]};
        choice.expected_std.clear();
        for (const int t : targets) choice.expected_std.push_back(std::sqrt(after(t, t)) * scale(t));
      }
      if (record >= options.max_record_s) break;
    }
  }
  if (!choice.step) {
    choice.why_none = "the model gives no finite sensitivity at any candidate step";
    return choice;
  }
  if (choice.step->expected_gain < options.min_gain) {
    choice.why_none = fmt::format("nothing measurable remains: the best step ({} at {:.3f} Hz) would lower log det of "
                                  "the targets' covariance by {:.2g} nats, below {:.2g}",
                                  choice.step->level, choice.step->frequency_hz, choice.step->expected_gain,
                                  options.min_gain);
    choice.step.reset();
    return choice;
  }
  std::vector<std::string> expected;
  for (std::size_t t = 0; t < targets.size(); ++t)
    expected.push_back(fmt::format("σ({}) {:.3g} → {:.3g}", options.targets[t],
                                   std::sqrt(fit.covariance(targets[t], targets[t])), choice.expected_std[t]));
  const auto why_sweep = sweep_why.find(choice.step->level);
  choice.step->reason = fmt::format("{}of {} candidates{} the most informative per second: {}",
                                    why_sweep != sweep_why.end() ? why_sweep->second : "", choice.candidates,
                                    focus ? " where the competing causes differ most," : "",
                                    fmt::join(expected, ", "));
  return choice;
}

}  // namespace beamid::solver
