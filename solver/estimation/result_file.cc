#include "solver/estimation/result_file.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

#include "hb/version.h"
#include "solver/estimation/fit_data.h"
#include "solver/estimation/fit_problem.h"
#include "solver/estimation/identify.h"
#include "solver/estimation/model_phasors.h"
#include "solver/estimation/whitened_misfit.h"

namespace beamid::solver {
namespace {

using Complex = std::complex<double>;

// √(Σσ²/Σ|Y|²) of each term.
PhasorUncertaintyBudget RelativeStd(const PhasorUncertaintyBudget& variance, double measured2) {
  const auto relative = [&](double v) { return std::sqrt(v / std::max(measured2, 1e-300)); };
  return {.noise = relative(variance.noise),
          .force = relative(variance.force),
          .frequency = relative(variance.frequency),
          .model_error = relative(variance.model_error)};
}

// Relative RMS error and χ² per fitted channel, harmonic and level.
std::vector<ChannelQuality> Quality(const FitData& fit, FitProblem& problem, const Eigen::VectorXd& x,
                                    const std::vector<ModelErrorEstimate>& model_errors) {
  const std::vector<Eigen::MatrixXcd> model = ModelPhasors(fit, problem, x);
  std::vector<ChannelQuality> out;
  for (std::size_t c = 0; c < fit.channels.size(); ++c) {
    ChannelQuality channel{.channel = fit.channels[c].channel};
    for (int k = 1; k <= fit.num_fit_harmonics; ++k) {
      std::vector<LevelQuality> per_level;
      for (const auto& level : fit.levels) {
        double error2 = 0.0, measured2 = 0.0, chi2 = 0.0;
        PhasorUncertaintyBudget variance;  // Σσ² term by term
        int count = 0;
        for (std::size_t i = 0; i < fit.steps.size(); ++i) {
          const FitStep& s = fit.steps[i];
          if (s.level != level) continue;
          const Complex misfit = model[i](c, k - 1) - s.measured(c, k - 1);
          error2 += std::norm(misfit);
          measured2 += std::norm(s.measured(c, k - 1));
          chi2 += Whitened(s, c, k, misfit).squaredNorm();
          if (!s.uncertainty_budget.empty()) {
            const PhasorUncertaintyBudget& u = s.uncertainty_budget[c][static_cast<std::size_t>(k - 1)];
            variance.noise += u.noise * u.noise;
            variance.force += u.force * u.force;
            variance.frequency += u.frequency * u.frequency;
            variance.model_error += u.model_error * u.model_error;
          }
          if (static_cast<std::size_t>(k) <= model_errors.size())
            variance.model_error += std::norm(model_errors[static_cast<std::size_t>(k - 1)].relative * model[i](c, 0));
          ++count;
        }
        per_level.push_back({.level = level,
                             .relative_rms_error = std::sqrt(error2 / std::max(measured2, 1e-300)),
                             .chi_square = chi2,
                             .num_steps = count,
                             .relative_std = RelativeStd(variance, measured2)});
      }
      channel.harmonics.push_back(std::move(per_level));
    }
    out.push_back(std::move(channel));
  }
  return out;
}

// Relative error of the predicted harmonics at every step of each held-out channel.
std::vector<HeldOutChannel> Validation(const FitData& validation, FitProblem& problem, const Eigen::VectorXd& x) {
  std::vector<HeldOutChannel> out;
  if (validation.channels.empty()) return out;
  const std::vector<Eigen::MatrixXcd> predicted = ModelPhasors(validation, problem, x);
  for (std::size_t c = 0; c < validation.channels.size(); ++c) {
    // A harmonic at the noise floor has a relative error of order one
    // whatever the model: the worst errors are taken where the measurement
    // resolves a kMeasurable error (its own relative uncertainty below
    // that), and the count of such steps is given.
    constexpr double kMeasurable = 0.01;
    HeldOutChannel channel{.channel = validation.channels[c].channel,
                           .position_m = validation.channels[c].position_m,
                           .measurable_relative_std = kMeasurable};
    for (std::size_t i = 0; i < validation.steps.size(); ++i) {
      const FitStep& s = validation.steps[i];
      HeldOutStep step{.level = s.level, .file = s.file, .frequency_hz = s.FrequencyHz()};
      for (int k = 1; k <= validation.num_fit_harmonics; ++k) {
        const Complex measured = s.measured(c, k - 1), model = predicted[i](c, k - 1);
        const double error = std::abs(model - measured) / std::max(std::abs(measured), 1e-300);
        const double relative_std = s.std_amplitude(c, k - 1) / std::max(std::abs(measured), 1e-300);
        step.harmonics.push_back(
            {.relative_error = error, .measured_relative_std = relative_std, .predicted = model, .measured = measured});
        if (relative_std > kMeasurable) continue;
        if (k == 1) {
          channel.worst_h1_relative_error = std::max(channel.worst_h1_relative_error, error);
          ++channel.measurable_steps_h1;
        }
        if (k == 3) {
          channel.worst_h3_relative_error = std::max(channel.worst_h3_relative_error, error);
          ++channel.measurable_steps_h3;
        }
      }
      channel.steps.push_back(std::move(step));
    }
    // No step resolves the error: there is no worst error to give (0 would
    // read as a perfect prediction).
    if (channel.measurable_steps_h1 == 0) channel.worst_h1_relative_error = std::numeric_limits<double>::quiet_NaN();
    if (channel.measurable_steps_h3 == 0) channel.worst_h3_relative_error = std::numeric_limits<double>::quiet_NaN();
    out.push_back(std::move(channel));
  }
  return out;
}

}  // namespace

ResultFile MakeResultFile(const FitData& fit, const FitData& validation, FitProblem& problem,
                          const IdentifyResult& result, const ResultContext& context) {
  if (context.family == nullptr) throw std::logic_error("MakeResultFile: no model family");
  ResultFile out;
  out.beamid_version = kVersion;
  out.campaign = {.folder = context.campaign_folder,
                  .name = context.campaign_name,
                  .absolute_folder = context.campaign_absolute_folder,
                  .sha256 = context.campaign_sha256};
  const ModelStructure& structure = problem.structure();
  out.model = {.kind = context.family->Kind(),
               .law = structure.law->Name(),
               .beam = fit.beam,
               .force_position_m = fit.force_position_m,
               .sensor_masses = fit.sensor_masses.point_masses,
               .fit_channels = {},
               .num_fit_harmonics = fit.num_fit_harmonics,
               .num_harmonics = problem.num_model_harmonics(),
               .phasor_uncertainty = fit.uncertainty};
  for (const auto& c : fit.channels) out.model.fit_channels.push_back(c.channel);
  for (const auto& p : result.parameters)
    out.parameters.push_back(
        {.name = p.name, .unit = p.unit, .value = p.value, .std = p.std, .lower_95 = p.lower_95, .upper_95 = p.upper_95,
         .std_model_error = p.std_model_error});
  for (const auto& l : structure.linear) out.linear_parameters.push_back(l.name);
  out.covariance = result.covariance;
  out.correlation = result.correlation;

  ResultFit& f = out.fit;
  f.chi_square = result.chi_square;
  f.degrees_of_freedom = result.degrees_of_freedom;
  f.reduced_chi_square = result.reduced_chi_square;
  f.model_errors = result.model_errors;
  f.seconds = result.seconds;
  for (const auto& s : result.starts)
    f.starts.push_back({.start = s.start,
                        .parameters = s.parameters,
                        .objective = s.objective,
                        .converged = s.success,
                        .iterations = s.iterations,
                        .status = s.status,
                        .states_seeded = s.route,
                        .branch_repairs = s.branch_repairs});
  f.best_start = result.best_start;
  f.starts_at_best = result.starts_at_best;
  f.verdict = result.verdict;
  for (const auto& m : result.minima.minima)
    f.minima.push_back({.parameters = m.parameters, .chi_square = m.chi_square, .num_starts = m.num_starts});
  f.second_minimum_chi_square_gap = result.minima.second_chi_square_gap;
  f.minimum_decisive = result.minima.decisive;
  f.direct_estimate = {.k1_Nm_rad = result.direct.k1_Nm_rad,
                       .k2_Nm_rad2 = result.direct.k2_Nm_rad2,
                       .k3_Nm_rad3 = result.direct.k3_Nm_rad3,
                       .c_Nms_rad = result.direct.c_Nms_rad,
                       .relative_residual = result.direct.relative_residual};
  out.warnings = result.warnings;

  out.quality = Quality(fit, problem, result.x, result.model_errors);
  out.validation = Validation(validation, problem, result.x);

  for (int i = 0; i < static_cast<int>(fit.steps.size()); ++i) {
    const FitStep& s = fit.steps[i];
    ResultStep step{.level = s.level, .file = s.file, .frequency_hz = s.FrequencyHz(), .force_N = s.force_N};
    step.state = problem.StepState(result.x, i);
    if (step.state.size() != context.family->StateSize(problem.num_model_harmonics()))
      throw std::logic_error("MakeResultFile: the problem's state is not its family's");
    out.steps.push_back(std::move(step));
  }
  return out;
}


}  // namespace beamid::solver
