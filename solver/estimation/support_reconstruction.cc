#include "solver/estimation/support_reconstruction.h"

#include <cmath>
#include <limits>
#include <numbers>

#include <Eigen/QR>

#include "hb/harmonic_balance.h"

namespace beamid::solver {

using hb::Complex;

std::vector<ReconstructedStep> ReconstructSupport(const FitData& data, const hb::LinearBeamModel& beam_model) {
  const int k_max = data.num_fit_harmonics;
  std::vector<double> positions;
  for (const auto& c : data.channels) positions.push_back(c.position_m);
  const hb::LinearBeam beam(beam_model, data.force_position_m);
  std::vector<ReconstructedStep> out;
  for (const FitStep& s : data.steps) {
    const hb::LinearHarmonics linear = hb::ComputeLinearHarmonics(beam, s.omega_rad_s, k_max, positions);
    ReconstructedStep step;
    step.omega_rad_s = s.omega_rad_s;
    step.theta_rad = Eigen::VectorXcd::Zero(k_max + 1);
    step.moment_Nm = Eigen::VectorXcd::Zero(k_max + 1);
    step.theta_std_rad = Eigen::VectorXd::Zero(k_max + 1);
    step.rotational_stiffness_Nm_rad = linear.rotational_stiffness.head(k_max + 1);
    for (int k = 1; k <= k_max; ++k) {
      const Complex force = k < s.force_N.size() ? s.force_N[k] : Complex(0.0);
      // Weighted least squares for one complex unknown: Θ = Σ w·ḡ·(Y − g_F·F) / Σ w·|g|².
      Complex numerator = 0.0;
      double denominator = 0.0;
      for (std::size_t c = 0; c < data.channels.size(); ++c) {
        const Complex factor = DerivativeFactor(data.channels[c].derivative_order, k * s.omega_rad_s);
        const Complex g = factor * linear.displacement_per_rotation(c, k);
        const Complex offset = factor * linear.displacement_per_force(c, k) * force;
        const double weight = 1.0 / std::pow(s.std_amplitude(c, k - 1), 2);
        numerator += weight * std::conj(g) * (s.measured(c, k - 1) - offset);
        denominator += weight * std::norm(g);
      }
      step.theta_rad[k] = numerator / denominator;
      step.theta_std_rad[k] = 1.0 / std::sqrt(denominator);
      step.moment_Nm[k] = linear.blocked_moment_per_force[k] * force - linear.rotational_stiffness[k] * step.theta_rad[k];
    }
    out.push_back(std::move(step));
  }
  return out;
}

DirectEstimate EstimatePolynomialDirectly(const std::vector<ReconstructedStep>& steps) {
  // Sample each period and regress the zero-mean moment on the zero-mean
  // regressors θ, θ², θ³ and θ̇ (the means are unobserved).
  constexpr int kSamples = 64;
  const int rows = static_cast<int>(steps.size()) * kSamples;
  Eigen::MatrixXd a(rows, 4);
  Eigen::VectorXd b(rows);
  int row = 0;
  double max_rotation = 0.0;
  for (const auto& s : steps) {
    Eigen::MatrixXd block(kSamples, 4);
    Eigen::VectorXd moment(kSamples);
    for (int n = 0; n < kSamples; ++n) {
      const double phase = 2.0 * std::numbers::pi * n / kSamples;
      double theta = 0.0, rate = 0.0, m = 0.0;
      for (Eigen::Index k = 1; k < s.theta_rad.size(); ++k) {
        const Complex e = std::polar(1.0, k * phase);
        theta += std::real(s.theta_rad[k] * e);
        rate += std::real(DerivativeFactor(1, k * s.omega_rad_s) * s.theta_rad[k] * e);
        m += std::real(s.moment_Nm[k] * e);
      }
      block.row(n) << theta, theta * theta, theta * theta * theta, rate;
      max_rotation = std::max(max_rotation, std::abs(theta));
      moment[n] = m;
    }
    block.rowwise() -= block.colwise().mean();
    a.middleRows(row, kSamples) = block;
    b.segment(row, kSamples) = moment.array() - moment.mean();
    row += kSamples;
  }
  // Column scaling keeps the normal equations well conditioned (θ ~ 1e-3).
  const Eigen::VectorXd scale = a.colwise().norm().cwiseMax(1e-300);
  const Eigen::MatrixXd scaled = a * scale.cwiseInverse().asDiagonal();
  // k1 ≥ 0 and c ≥ 0: try every active set of the two bounds, keep the best feasible.
  double best_residual = std::numeric_limits<double>::infinity();
  Eigen::Vector4d best = Eigen::Vector4d::Zero();
  for (int active = 0; active < 4; ++active) {
    std::vector<int> free;
    for (int j = 0; j < 4; ++j) {
      const bool clamped = (j == 0 && (active & 1)) || (j == 3 && (active & 2));
      if (!clamped) free.push_back(j);
    }
    Eigen::MatrixXd sub(rows, free.size());
    for (std::size_t j = 0; j < free.size(); ++j) sub.col(j) = scaled.col(free[j]);
    const Eigen::VectorXd solution = sub.colPivHouseholderQr().solve(b);
    Eigen::Vector4d full = Eigen::Vector4d::Zero();
    for (std::size_t j = 0; j < free.size(); ++j) full[free[j]] = solution[j] / scale[free[j]];
    if (full[0] < 0.0 || full[3] < 0.0) continue;
    const double residual = (a * full - b).norm();
    if (residual < best_residual) {
      best_residual = residual;
      best = full;
    }
  }
  return {.k1_Nm_rad = best[0], .k2_Nm_rad2 = best[1], .k3_Nm_rad3 = best[2], .c_Nms_rad = best[3],
          .relative_residual = best_residual / std::max(b.norm(), 1e-300),
          .max_rotation_rad = max_rotation};
}

}  // namespace beamid::solver
