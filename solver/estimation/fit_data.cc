#include "solver/estimation/fit_data.h"

#include "hb/errors.h"
#include "hb/option_checks.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <Eigen/Cholesky>
#include <Eigen/LU>

namespace beamid::solver {
namespace {

bool IsSignificant(const signal::HarmonicPhasor& h, double chi2_threshold) {
  const Eigen::Vector2d x(h.value.real(), h.value.imag());
  const Eigen::Matrix2d covariance = h.Covariance();
  // A phasor without an uncertainty (noise-free data) is taken as it is.
  if (!(covariance.trace() > 0.0)) return true;
  return x.dot(covariance.ldlt().solve(x)) >= chi2_threshold;
}

}  // namespace


void FitDataOptions::Validate() const {
  using namespace option_checks;
  RequireInRange("FitDataOptions.num_fit_harmonics", num_fit_harmonics, 1, kMaxHarmonics);
  // Zero would give noise-free data infinite weight; at 1 or above the floor
  // would exceed the largest fundamental itself.
  if (!(relative_uncertainty_floor > 0.0 && relative_uncertainty_floor < 1.0))
    Refuse("FitDataOptions.relative_uncertainty_floor", FormatValue(relative_uncertainty_floor), "above 0 and below 1");
  // At 1 or above the model's error would exceed the phasor itself.
  if (!(relative_model_error >= 0.0 && relative_model_error < 1.0))
    Refuse("FitDataOptions.relative_model_error", FormatValue(relative_model_error), "at least 0 and below 1");
  if (!(force_harmonic_family_significance > 0.0 && force_harmonic_family_significance < 1.0))
    Refuse("FitDataOptions.force_harmonic_family_significance", FormatValue(force_harmonic_family_significance),
           "above 0 and below 1");
}

double FitDataOptions::ForceHarmonicChiSquareThreshold(int num_tested) const {
  // χ² with 2 dof has the upper tail e^(−q/2).
  return -2.0 * std::log(force_harmonic_family_significance / std::max(1, num_tested));
}

FitData MakeFitData(const signal::Campaign& campaign, const signal::PhasorSet& phasors,
                    const FitDataOptions& options) {
  options.Validate();
  if (campaign.excitation.quantity != signal::Quantity::kForce)
    // The model is driven by a point force: a voltage's force changes with
    // the amplifier and shaker near resonance, a base excitation is another
    // load; fitting either as a force would print wrong parameters.
    throw InputError((campaign.folder / "campaign.json").string(), campaign.excitation.channel,
                     "the excitation is a " + std::string(signal::QuantityName(campaign.excitation.quantity)) +
                         ", but the model-based tools (identify, diagnose, predict) need the force applied to the "
                         "beam",
                     "measure the force with a force transducer at the drive point, or use the model-free tools "
                     "(beamid extract, beamid backbone --measured), which work with any excitation");
  if (phasors.num_harmonics < options.num_fit_harmonics)
    throw std::invalid_argument("the phasors hold " + std::to_string(phasors.num_harmonics) +
                                " harmonics, the fit needs " + std::to_string(options.num_fit_harmonics) +
                                " (re-extract with -H " + std::to_string(options.num_fit_harmonics) + ")");
  FitData data;
  data.beam = campaign.beam;
  data.force_position_m = campaign.excitation.position_m;
  data.num_fit_harmonics = options.num_fit_harmonics;
  data.uncertainty = options.uncertainty;
  for (const auto& sensor : campaign.sensors)
    if (sensor.mass_kg && *sensor.mass_kg > 0.0)
      data.sensor_masses.point_masses.push_back({sensor.position_m, *sensor.mass_kg});
  std::vector<std::string> names = options.channels;
  if (names.empty())
    for (const auto& sensor : campaign.sensors)
      if (campaign.Use(sensor.channel) != signal::ChannelUse::kIgnored) names.push_back(sensor.channel);
  // A fit of no channel has no residual: its parameters would be the start's.
  if (names.empty())
    throw InputError((campaign.folder / "campaign.json").string(), "",
                     "no sensor is left to fit: every sensor is listed in ignore_channels",
                     "remove a sensor from ignore_channels");
  for (std::size_t i = 0; i < names.size(); ++i)
    if (std::find(names.begin(), names.begin() + static_cast<std::ptrdiff_t>(i), names[i]) != names.begin() + static_cast<std::ptrdiff_t>(i))
      // Fitted twice, a channel would count double and its σ shrink by √2.
      throw InputError("channel '" + names[i] + "' is listed twice: list every channel once");
  for (const auto& name : names) {
    const auto it = std::find_if(campaign.sensors.begin(), campaign.sensors.end(),
                                 [&](const signal::ChannelSpec& s) { return s.channel == name; });
    if (it == campaign.sensors.end()) {
      std::string known;
      for (const auto& s : campaign.sensors) known += (known.empty() ? "" : ", ") + s.channel;
      throw std::invalid_argument("channel '" + name + "' is not a sensor of the campaign (sensors: " + known + ")");
    }
    data.channels.push_back({it->channel, it->position_m, signal::DerivativeOrder(it->quantity)});
  }

  const int channels = static_cast<int>(data.channels.size());
  const int k_max = options.num_fit_harmonics;
  std::vector<double> largest(channels, 0.0);
  for (const auto& step : phasors.steps)
    for (int c = 0; c < channels; ++c)
      if (const auto* p = step.Find(data.channels[c].channel)) largest[c] = std::max(largest[c], p->Harmonic(1).Amplitude());
  // Each step's neighbours on its level, in acquisition order, for ∂Y/∂ω.
  std::vector<std::vector<std::size_t>> level_steps;
  std::vector<std::pair<std::size_t, std::size_t>> place(phasors.steps.size());  // (level, index in it)
  {
    std::vector<std::string> labels;
    for (std::size_t i = 0; i < phasors.steps.size(); ++i) {
      const auto it = std::find(labels.begin(), labels.end(), phasors.steps[i].level);
      const std::size_t l = static_cast<std::size_t>(it - labels.begin());
      if (it == labels.end()) {
        labels.push_back(phasors.steps[i].level);
        level_steps.emplace_back();
      }
      place[i] = {l, level_steps[l].size()};
      level_steps[l].push_back(i);
    }
  }

  int force_harmonics_tested = 0;
  for (const auto& step : phasors.steps)
    for (const auto& h : step.force.harmonics) force_harmonics_tested += h.harmonic >= 2;
  const double force_threshold = options.ForceHarmonicChiSquareThreshold(force_harmonics_tested);
  for (std::size_t i = 0; i < phasors.steps.size(); ++i) {
    const signal::StepPhasors& step = phasors.steps[i];
    FitStep fit;
    fit.level = step.level;
    fit.file = step.file;
    fit.omega_rad_s = step.Omega_rad_s();
    fit.nominal_frequency_hz = step.nominal_frequency_hz;
    fit.unsettled = step.quality.unsettled;
    fit.unsettled_change_relative = step.quality.unsettled_change_relative;
    fit.force_N = Eigen::VectorXcd::Zero(phasors.num_harmonics + 1);
    for (const auto& h : step.force.harmonics) {
      if (h.harmonic >= 2 && !IsSignificant(h, force_threshold)) continue;
      fit.force_N[h.harmonic] = h.value;
    }
    // F_1 is the phase reference (real, positive): its real part's σ is
    // that of its amplitude.
    const signal::HarmonicPhasor& f1 = step.force.Harmonic(1);
    const double force_relative_std = f1.Amplitude() > 0.0 ? std::sqrt(f1.Covariance()(0, 0)) / f1.Amplitude() : 0.0;
    const double omega_std_rad_s = 2.0 * std::numbers::pi * step.frequency_std_hz;
    // The step and its neighbours on its level: all ∂Y/∂ω needs.
    const auto& [level, index] = place[i];
    const std::vector<std::size_t>& on_level = level_steps[level];
    const std::size_t first = index > 0 ? index - 1 : 0, last = std::min(index + 1, on_level.size() - 1);
    std::vector<double> around_omega;
    for (std::size_t n = first; n <= last; ++n) around_omega.push_back(phasors.steps[on_level[n]].Omega_rad_s());
    fit.measured.resize(channels, k_max);
    fit.std_amplitude.resize(channels, k_max);
    fit.whitening.resize(channels);
    fit.uncertainty_budget.resize(channels);
    const bool propagated = options.uncertainty == PhasorUncertainty::kPropagated;
    // A harmonic fit over whole periods of a record with white noise gives
    // F_1's cosine and sine parts the same σ: its phase's σ is its amplitude's
    // relative σ (the extractor keeps only the latter once F_1 is the reference).
    const double force_phase_std_rad = force_relative_std;
    if (propagated) fit.shared_errors.assign(3, Eigen::MatrixXcd::Zero(channels, k_max));
    for (int c = 0; c < channels; ++c) {
      const auto* p = step.Find(data.channels[c].channel);
      if (!p) throw std::invalid_argument(step.file + ": no phasors for channel " + data.channels[c].channel);
      for (int k = 1; k <= k_max; ++k) {
        const signal::HarmonicPhasor& h = p->Harmonic(k);
        PhasorUncertaintyBudget budget;
        Eigen::Matrix2d covariance;
        if (propagated) {
          std::vector<std::complex<double>> around_values;
          std::vector<double> around_noise;
          for (std::size_t n = first; n <= last; ++n) {
            const auto* q = phasors.steps[on_level[n]].Find(data.channels[c].channel);
            const signal::HarmonicPhasor& other = q ? q->Harmonic(k) : h;
            around_values.push_back(other.value);
            around_noise.push_back(std::sqrt(0.5 * other.Covariance().trace()));
          }
          // Noise-free data (simulations) must not get an infinite weight;
          // a billionth of the channel's largest fundamental never shows
          // beside real noise.
          const std::complex<double> slope = NeighbourSlope(around_omega, around_values, around_noise, index - first);
          covariance = PhasorCovariance({h.value, h.Covariance()}, k, force_relative_std, slope, omega_std_rad_s,
                                        options.relative_model_error, 1e-9 * largest[c], &budget);
          fit.shared_errors[0](c, k - 1) = static_cast<double>(k) * force_relative_std * h.value;
          fit.shared_errors[1](c, k - 1) = std::complex<double>(0.0, -k * force_phase_std_rad) * h.value;
          fit.shared_errors[2](c, k - 1) = omega_std_rad_s * slope;
        } else {
          const double floor = options.relative_uncertainty_floor * largest[c];
          covariance = h.Covariance() + floor * floor * Eigen::Matrix2d::Identity();
          budget = {.noise = std::sqrt(0.5 * h.Covariance().trace()), .model_error = floor};
        }
        fit.measured(c, k - 1) = h.value;
        fit.std_amplitude(c, k - 1) = std::sqrt(0.5 * covariance.trace());
        fit.uncertainty_budget[c].push_back(budget);
        const Eigen::Matrix2d lower = covariance.llt().matrixL();
        fit.whitening[c].push_back(lower.inverse());
      }
    }
    if (std::find(data.levels.begin(), data.levels.end(), fit.level) == data.levels.end())
      data.levels.push_back(fit.level);
    data.steps.push_back(std::move(fit));
  }
  if (data.steps.empty()) throw std::invalid_argument("the campaign has no steps to fit");
  return data;
}

double FitData::MeanOmega_rad_s() const {
  double sum = 0.0;
  for (const auto& s : steps) sum += s.omega_rad_s;
  return steps.empty() ? 1.0 : sum / static_cast<double>(steps.size());
}

}  // namespace beamid::solver
