#include "solver/estimation/identification_report.h"

#include "solver/estimation/model_phasors.h"

#include <cmath>
#include <map>
#include <numbers>

namespace beamid::solver {
namespace {

using Complex = std::complex<double>;

nlohmann::json ToJson(const Eigen::VectorXcd& phasors) {
  nlohmann::json out = nlohmann::json::array();
  for (const auto& p : phasors) out.push_back({p.real(), p.imag()});
  return out;
}

nlohmann::json ToJson(const Eigen::MatrixXd& m) {
  nlohmann::json out = nlohmann::json::array();
  for (Eigen::Index r = 0; r < m.rows(); ++r) {
    nlohmann::json row = nlohmann::json::array();
    for (Eigen::Index c = 0; c < m.cols(); ++c) row.push_back(m(r, c));
    out.push_back(row);
  }
  return out;
}

}  // namespace

nlohmann::json IdentificationReport(const FitData& fit, const FitData& validation, FitProblem& problem,
                                    const IdentifyResult& result, const ReportContext& context) {
  nlohmann::json out;
  out["format"] = "beamid-result/1";
  out["command"] = "identify";
  out["campaign"] = {{"folder", context.campaign_folder}, {"name", context.campaign_name}};
  const ModelStructure& structure = problem.structure();
  nlohmann::json masses = nlohmann::json::array();
  for (const auto& m : fit.sensor_masses.point_masses) masses.push_back({{"position_m", m.position_m}, {"mass_kg", m.mass_kg}});
  nlohmann::json channels = nlohmann::json::array();
  for (const auto& c : fit.channels) channels.push_back(c.channel);
  out["model"] = {{"kind", context.model_kind},
                  {"law", structure.law->Name()},
                  {"beam",
                   {{"length_m", fit.beam.length_m},
                    {"width_m", fit.beam.width_m},
                    {"thickness_m", fit.beam.thickness_m},
                    {"youngs_modulus_Pa", fit.beam.youngs_modulus_Pa},
                    {"density_kg_m3", fit.beam.density_kg_m3},
                    {"loss_factor", fit.beam.loss_factor}}},
                  {"force_position_m", fit.force_position_m},
                  {"sensor_masses", masses},
                  {"fit_channels", channels},
                  {"num_fit_harmonics", fit.num_fit_harmonics},
                  {"num_harmonics", problem.num_model_harmonics()}};
  nlohmann::json parameters = nlohmann::json::object();
  nlohmann::json order = nlohmann::json::array();
  for (const auto& p : result.parameters) {
    parameters[p.name] = {{"value", p.value}, {"std", p.std}, {"unit", p.unit}, {"ci95", {p.lower_95, p.upper_95}}};
    order.push_back(p.name);
  }
  nlohmann::json linear = nlohmann::json::array();
  for (const auto& l : structure.linear) linear.push_back(l.name);
  out["parameters"] = parameters;
  out["parameter_order"] = order;
  out["linear_parameters"] = linear;
  out["covariance"] = ToJson(result.covariance);
  out["correlation"] = ToJson(result.correlation);
  nlohmann::json starts = nlohmann::json::array();
  for (const auto& s : result.starts)
    starts.push_back({{"start", s.start}, {"parameters", s.parameters}, {"objective", s.objective},
                      {"converged", s.success}, {"iterations", s.iterations}, {"status", s.status},
                      {"states_seeded", s.route == StartRoute::kMeasuredStates ? "measured" : "feasible"},
                      {"branch_repairs", s.branch_repairs}});
  nlohmann::json minima = nlohmann::json::array();
  for (const auto& m : result.minima.minima)
    minima.push_back({{"parameters", m.parameters}, {"chi_square", m.chi_square}, {"starts", m.num_starts}});
  out["fit"] = {{"chi_square", result.chi_square},
                {"degrees_of_freedom", result.degrees_of_freedom},
                {"reduced_chi_square", result.reduced_chi_square},
                {"seconds", result.seconds},
                {"starts", starts},
                {"best_start", result.best_start},
                {"starts_at_best", result.starts_at_best},
                {"minima", minima},
                {"second_minimum_chi_square_gap", result.minima.second_chi_square_gap},
                {"minimum_decisive", result.minima.decisive},
                {"direct_estimate",
                 {{"k1", result.direct.k1_Nm_rad}, {"k2", result.direct.k2_Nm_rad2}, {"k3", result.direct.k3_Nm_rad3},
                  {"c", result.direct.c_Nms_rad}, {"relative_residual", result.direct.relative_residual}}}};
  out["warnings"] = result.warnings;

  // Quality per channel, harmonic and level: relative RMS error and χ².
  const std::vector<Eigen::MatrixXcd> model = ModelPhasors(fit, problem, result.x);
  nlohmann::json quality = nlohmann::json::object();
  for (std::size_t c = 0; c < fit.channels.size(); ++c) {
    nlohmann::json per_harmonic = nlohmann::json::object();
    for (int k = 1; k <= fit.num_fit_harmonics; ++k) {
      nlohmann::json per_level = nlohmann::json::object();
      for (const auto& level : fit.levels) {
        double error2 = 0.0, measured2 = 0.0, chi2 = 0.0;
        int count = 0;
        for (std::size_t i = 0; i < fit.steps.size(); ++i) {
          const FitStep& s = fit.steps[i];
          if (s.level != level) continue;
          const Complex misfit = model[i](c, k - 1) - s.measured(c, k - 1);
          error2 += std::norm(misfit);
          measured2 += std::norm(s.measured(c, k - 1));
          chi2 += (s.whitening[c][k - 1] * Eigen::Vector2d(misfit.real(), misfit.imag())).squaredNorm();
          ++count;
        }
        per_level[level] = {{"relative_rms_error", std::sqrt(error2 / std::max(measured2, 1e-300))},
                            {"chi_square", chi2},
                            {"steps", count}};
      }
      per_harmonic["h" + std::to_string(k)] = per_level;
    }
    quality[fit.channels[c].channel] = per_harmonic;
  }
  out["quality"] = quality;

  // Held-out channels: relative error of the predicted harmonics at every step.
  if (!validation.channels.empty()) {
    const std::vector<Eigen::MatrixXcd> predicted = ModelPhasors(validation, problem, result.x);
    nlohmann::json held_out = nlohmann::json::object();
    for (std::size_t c = 0; c < validation.channels.size(); ++c) {
      nlohmann::json steps = nlohmann::json::array();
      // A harmonic at the noise floor has a relative error of order one
      // whatever the model: the worst errors are taken where the
      // measurement resolves a kMeasurable error (its own relative
      // uncertainty below that), and the count of such steps is given.
      constexpr double kMeasurable = 0.01;
      double worst_h1 = 0.0, worst_h3 = 0.0;
      int measurable_h1 = 0, measurable_h3 = 0;
      for (std::size_t i = 0; i < validation.steps.size(); ++i) {
        const FitStep& s = validation.steps[i];
        nlohmann::json step = {{"level", s.level}, {"file", s.file},
                               {"frequency_Hz", s.omega_rad_s / (2 * std::numbers::pi)}};
        for (int k = 1; k <= validation.num_fit_harmonics; ++k) {
          const double error = std::abs(predicted[i](c, k - 1) - s.measured(c, k - 1)) /
                               std::max(std::abs(s.measured(c, k - 1)), 1e-300);
          const double relative_std = s.std_amplitude(c, k - 1) / std::max(std::abs(s.measured(c, k - 1)), 1e-300);
          step["h" + std::to_string(k) + "_relative_error"] = error;
          step["h" + std::to_string(k) + "_measured_relative_std"] = relative_std;
          step["h" + std::to_string(k) + "_predicted"] = {predicted[i](c, k - 1).real(), predicted[i](c, k - 1).imag()};
          step["h" + std::to_string(k) + "_measured"] = {s.measured(c, k - 1).real(), s.measured(c, k - 1).imag()};
          if (relative_std > kMeasurable) continue;
          if (k == 1) worst_h1 = std::max(worst_h1, error), ++measurable_h1;
          if (k == 3) worst_h3 = std::max(worst_h3, error), ++measurable_h3;
        }
        steps.push_back(step);
      }
      held_out[validation.channels[c].channel] = {{"position_m", validation.channels[c].position_m},
                                                  {"worst_h1_relative_error", worst_h1},
                                                  {"worst_h3_relative_error", worst_h3},
                                                  {"measurable_relative_std", kMeasurable},
                                                  {"measurable_steps_h1", measurable_h1},
                                                  {"measurable_steps_h3", measurable_h3},
                                                  {"steps", steps}};
    }
    out["validation"] = held_out;
  }

  nlohmann::json steps = nlohmann::json::array();
  for (int i = 0; i < static_cast<int>(fit.steps.size()); ++i) {
    const FitStep& s = fit.steps[i];
    steps.push_back({{"level", s.level},
                     {"file", s.file},
                     {"frequency_Hz", s.omega_rad_s / (2 * std::numbers::pi)},
                     {"force_N", ToJson(s.force_N)},
                     {problem.StepStateName(), ToJson(problem.StepState(result.x, i))}});
  }
  out["steps"] = steps;
  return out;
}

}  // namespace beamid::solver
