#include "solver/estimation/model_error.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <stdexcept>
#include <string>

#include <Eigen/LU>

#include "solver/estimation/chi_square.h"

namespace beamid::solver {
namespace {

// Q(ε) of the header.
double Misfit(const std::vector<ModelErrorPhasor>& phasors, double relative) {
  double q = 0.0;
  for (const ModelErrorPhasor& p : phasors) {
    const double added = relative * relative * p.scale * p.scale;
    const Eigen::Matrix2d total = p.covariance + added * Eigen::Matrix2d::Identity();
    q += p.residual.dot(total.inverse() * p.residual);
  }
  return q;
}

// The ε ≥ 0 with Q(ε) = target (0 when Q(0) ≤ target already).
double RelativeErrorAt(const std::vector<ModelErrorPhasor>& phasors, double target, double sum_residual2,
                       double mean_scale2) {
  if (Misfit(phasors, 0.0) <= target) return 0.0;
  // Bracket from the plain estimate Σ|r|²/(ν·mean a²) and widen until Q is below target.
  double high = std::sqrt(sum_residual2 / (target * mean_scale2));
  while (Misfit(phasors, high) > target) high *= 2.0;
  double low = 0.0;
  for (int i = 0; i < 200 && high - low > 1e-12 * high; ++i) {
    const double middle = 0.5 * (low + high);
    (Misfit(phasors, middle) > target ? low : high) = middle;
  }
  return 0.5 * (low + high);
}

}  // namespace

ModelErrorEstimate EstimateModelError(const std::vector<ModelErrorPhasor>& phasors, double degrees_of_freedom) {
  if (!(degrees_of_freedom > 0.0))
    throw std::invalid_argument("EstimateModelError: degrees of freedom " + std::to_string(degrees_of_freedom) +
                                " (need > 0)");
  double sum_residual2 = 0.0, sum_scale2 = 0.0;
  for (const ModelErrorPhasor& p : phasors) {
    if (!(p.covariance.determinant() > 0.0 && p.covariance.trace() > 0.0))
      throw std::invalid_argument("EstimateModelError: a phasor's covariance is not positive definite");
    sum_residual2 += p.residual.squaredNorm();
    sum_scale2 += p.scale * p.scale;
  }
  if (!(sum_scale2 > 0.0))
    throw std::invalid_argument("EstimateModelError: every phasor's magnitude is 0 (a relative error scales nothing)");
  const double mean_scale2 = sum_scale2 / static_cast<double>(phasors.size());
  ModelErrorEstimate e{.chi_square = Misfit(phasors, 0.0), .degrees_of_freedom = degrees_of_freedom};
  e.relative = RelativeErrorAt(phasors, degrees_of_freedom, sum_residual2, mean_scale2);
  e.lower_95 = RelativeErrorAt(phasors, ChiSquareUpperQuantile(0.025, degrees_of_freedom), sum_residual2, mean_scale2);
  e.upper_95 = RelativeErrorAt(phasors, ChiSquareUpperQuantile(0.975, degrees_of_freedom), sum_residual2, mean_scale2);
  return e;
}

std::vector<ModelErrorEstimate> EstimateModelErrors(const FitData& data, const std::vector<Eigen::MatrixXcd>& model,
                                                    int degrees_of_freedom) {
  if (model.size() != data.steps.size())
    throw std::invalid_argument("EstimateModelErrors: the model's phasors are not the data's steps");
  const int k_max = data.num_fit_harmonics;
  const double dof_per_residual = static_cast<double>(degrees_of_freedom) / std::max(1, data.NumResiduals());
  std::vector<ModelErrorEstimate> out;
  for (int k = 1; k <= k_max; ++k) {
    std::vector<ModelErrorPhasor> phasors;
    bool any_model = false;
    for (std::size_t i = 0; i < data.steps.size(); ++i) {
      const FitStep& s = data.steps[i];
      for (std::size_t c = 0; c < data.channels.size(); ++c) {
        const std::complex<double> misfit =
            model[i](static_cast<Eigen::Index>(c), k - 1) - s.measured(static_cast<Eigen::Index>(c), k - 1);
        const double fundamental = std::abs(model[i](static_cast<Eigen::Index>(c), 0));
        const Eigen::Matrix2d root = s.whitening[c][static_cast<std::size_t>(k - 1)].inverse();  // L
        phasors.push_back({.residual = Eigen::Vector2d(misfit.real(), misfit.imag()),
                           .covariance = root * root.transpose(),
                           .scale = fundamental});
        any_model = any_model || fundamental > 0.0;
      }
    }
    const double dof = dof_per_residual * 2.0 * static_cast<double>(phasors.size());
    if (!any_model || phasors.empty() || !(dof > 0.0)) {
      out.push_back({.degrees_of_freedom = dof});
      continue;
    }
    out.push_back(EstimateModelError(phasors, dof));
  }
  return out;
}

Eigen::MatrixXd ModelErrorInformation(const FitData& data, const std::vector<Eigen::MatrixXcd>& model,
                                      const std::vector<ModelErrorEstimate>& errors,
                                      const Eigen::MatrixXd& whitened_jacobian) {
  if (whitened_jacobian.rows() != data.NumResiduals() || model.size() != data.steps.size())
    throw std::invalid_argument("ModelErrorInformation: the Jacobian's rows or the model's steps are not the data's");
  const int channels = static_cast<int>(data.channels.size());
  const int k_max = data.num_fit_harmonics;
  const Eigen::Index rows_per_step = 2 * channels * k_max;
  Eigen::MatrixXd extra = Eigen::MatrixXd::Zero(whitened_jacobian.cols(), whitened_jacobian.cols());
  for (std::size_t s = 0; s < data.steps.size(); ++s)
    for (int c = 0; c < channels; ++c)
      for (int k = 1; k <= std::min(k_max, static_cast<int>(errors.size())); ++k) {
        const double std = errors[static_cast<std::size_t>(k - 1)].relative * std::abs(model[s](c, 0));
        if (std == 0.0) continue;
        const Eigen::Matrix2d& whitening =
            data.steps[s].whitening[static_cast<std::size_t>(c)][static_cast<std::size_t>(k - 1)];
        const auto rows =
            whitened_jacobian.middleRows<2>(static_cast<Eigen::Index>(s) * rows_per_step + 2 * (c * k_max + k - 1));
        const Eigen::MatrixXd t = whitening.transpose() * rows;  // L⁻ᵀ·J_i
        extra += std * std * t.transpose() * t;
      }
  return extra;
}

}  // namespace beamid::solver
