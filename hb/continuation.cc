#include "hb/continuation.h"

#include <cmath>
#include <stdexcept>

#include <Eigen/LU>

#include "hb/option_checks.h"

namespace beamid::hb {
namespace {

struct PathPoint {
  Eigen::VectorXd y;  // scaled [z; ω]
  Eigen::MatrixXd jacobian_z;
  Eigen::VectorXd jacobian_omega;
};

}  // namespace

void ContinuationOptions::Validate() const {
  using namespace option_checks;
  RequirePositive("ContinuationOptions.omega_start_rad_s", omega_start_rad_s);
  RequirePositive("ContinuationOptions.omega_end_rad_s", omega_end_rad_s);
  if (omega_end_rad_s == omega_start_rad_s)
    Refuse("ContinuationOptions.omega_end_rad_s", FormatValue(omega_end_rad_s), "other than omega_start_rad_s");
  RequireAtLeast("ContinuationOptions.max_points", max_points, 1);
  RequirePositive("ContinuationOptions.min_step", min_step);
  RequireAtLeast("ContinuationOptions.max_step", max_step, min_step);
  RequireInRange("ContinuationOptions.initial_step", initial_step, min_step, max_step);
  RequireAtLeast("ContinuationOptions.target_iterations", target_iterations, 1);
  RequireAtLeast("ContinuationOptions.max_iterations", max_iterations, 1);
  RequirePositive("ContinuationOptions.tolerance", tolerance);
}

ContinuationSummary TraceFrequencyResponse(const HarmonicBalance& balance, const Eigen::VectorXcd& force_N,
                                           const ContinuationOptions& options,
                                           const std::function<void(double)>& progress) {
  options.Validate();
  const int m = balance.num_unknowns();
  const double direction = options.omega_end_rad_s > options.omega_start_rad_s ? 1.0 : -1.0;
  const double omega_ref = options.omega_start_rad_s;

  ContinuationSummary summary;
  const HarmonicBalanceSolution first = balance.Solve(options.omega_start_rad_s, force_N);
  if (!first.converged) {
    summary.message = "no converged harmonic balance solution at the start frequency";
    return summary;
  }
  // Amplitude scale: the largest linear response over the range, so that a
  // step means the same near the peak as far from it.
  const Eigen::VectorXd z0 = HarmonicBalance::ToReal(first.theta_rad);
  double z_ref = z0.norm();
  constexpr int kScaleSamples = 64;
  for (int i = 0; i <= kScaleSamples; ++i) {
    const double omega = options.omega_start_rad_s +
                         (options.omega_end_rad_s - options.omega_start_rad_s) * i / kScaleSamples;
    const LinearHarmonics linear = balance.Linear(omega);
    const double k1 = balance.law().InitialStiffness_Nm_rad(), c = balance.law().InitialDamping_Nms_rad();
    const Complex theta = linear.blocked_moment_per_force[1] * PadHarmonics(force_N, 1)[1] /
                          (linear.rotational_stiffness[1] + Complex(k1, omega * c));
    z_ref = std::max(z_ref, std::abs(theta));
  }
  z_ref = std::max(z_ref, 1e-12);

  auto unscale = [&](const Eigen::VectorXd& y, Eigen::VectorXd* z) {
    *z = y.head(m) * z_ref;
    return y[m] * omega_ref;
  };
  // ∂R/∂ω costs a second linear evaluation: the corrector reuses the one of
  // its first iterate (a chord step in ω), converged points get a fresh one.
  auto evaluate = [&](const Eigen::VectorXd& y, Eigen::VectorXd* r, PathPoint* point, bool with_omega) {
    Eigen::VectorXd z;
    const double omega = unscale(y, &z);
    const LinearHarmonics linear = balance.Linear(omega);
    balance.Residual(z, linear, force_N, r, &point->jacobian_z, with_omega ? &point->jacobian_omega : nullptr);
    // Chain rule into scaled coordinates.
    point->jacobian_z *= z_ref;
    if (with_omega) point->jacobian_omega *= omega_ref;
  };
  auto tangent_at = [&](const PathPoint& point, const Eigen::VectorXd& previous) {
    Eigen::MatrixXd bordered(m + 1, m + 1);
    bordered << point.jacobian_z, point.jacobian_omega, previous.transpose();
    Eigen::VectorXd rhs = Eigen::VectorXd::Zero(m + 1);
    rhs[m] = 1.0;
    Eigen::VectorXd t = bordered.partialPivLu().solve(rhs);
    return Eigen::VectorXd(t / t.norm());
  };
  auto det_sign = [](const Eigen::MatrixXd& j) { return j.partialPivLu().determinant() >= 0.0 ? 1 : -1; };
  auto record = [&](const PathPoint& point, int reference_sign) {
    Eigen::VectorXd z;
    FrequencyResponsePoint out;
    out.omega_rad_s = unscale(point.y, &z);
    out.theta_rad = HarmonicBalance::ToComplex(z);
    out.stable = det_sign(point.jacobian_z) == reference_sign;
    summary.points.push_back(std::move(out));
  };

  PathPoint current;
  current.y.resize(m + 1);
  current.y << z0 / z_ref, options.omega_start_rad_s / omega_ref;
  Eigen::VectorXd r;
  evaluate(current.y, &r, &current, true);
  const int reference_sign = det_sign(current.jacobian_z);
  record(current, reference_sign);
  Eigen::VectorXd previous_tangent = Eigen::VectorXd::Zero(m + 1);
  previous_tangent[m] = direction;
  Eigen::VectorXd tangent = tangent_at(current, previous_tangent);

  double step = options.initial_step;
  const double span = std::abs(options.omega_end_rad_s - options.omega_start_rad_s);
  while (static_cast<int>(summary.points.size()) < options.max_points) {
    const Eigen::VectorXd predicted = current.y + step * tangent;
    PathPoint next;
    next.y = predicted;
    bool converged = false;
    int iterations = 0;
    for (; iterations < options.max_iterations; ++iterations) {
      evaluate(next.y, &r, &next, iterations == 0);
      Eigen::MatrixXd bordered(m + 1, m + 1);
      bordered << next.jacobian_z, next.jacobian_omega, tangent.transpose();
      Eigen::VectorXd rhs(m + 1);
      rhs << -r, -tangent.dot(next.y - predicted);
      const Eigen::VectorXd delta = bordered.partialPivLu().solve(rhs);
      if (!delta.allFinite()) break;
      next.y += delta;
      if (delta.norm() <= options.tolerance * (1.0 + next.y.norm())) {
        converged = true;
        evaluate(next.y, &r, &next, true);
        break;
      }
    }
    if (!converged) {
      step *= 0.5;
      if (step < options.min_step) {
        summary.message = "step size fell below min_step (the curve may end or bifurcate here)";
        break;
      }
      continue;
    }
    const Eigen::VectorXd next_tangent = tangent_at(next, tangent);
    const int sign_before = det_sign(current.jacobian_z), sign_after = det_sign(next.jacobian_z);
    if (sign_before != sign_after) ++summary.num_turning_points;
    current = std::move(next);
    tangent = next_tangent;
    record(current, reference_sign);

    const double omega = current.y[m] * omega_ref;
    if (progress) progress(std::min(1.0, std::abs(omega - options.omega_start_rad_s) / span));
    if ((omega - options.omega_end_rad_s) * direction >= 0.0) {
      summary.reached_end = true;
      break;
    }
    if (iterations < options.target_iterations) step = std::min(step * 1.5, options.max_step);
    if (iterations > options.target_iterations) step = std::max(step * 0.7, options.min_step);
  }
  if (summary.message.empty())
    summary.message = summary.reached_end ? "reached the end frequency" : "stopped at max_points";
  return summary;
}

}  // namespace beamid::hb
