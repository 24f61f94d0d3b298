#include "hb/backbone.h"

#include <cmath>
#include <stdexcept>

#include <Eigen/LU>

#include "hb/option_checks.h"

namespace beamid::hb {

void BackboneOptions::Validate() const {
  using namespace option_checks;
  RequirePositive("BackboneOptions.min_theta_amplitude_rad", min_theta_amplitude_rad);
  RequireAbove("BackboneOptions.max_theta_amplitude_rad", max_theta_amplitude_rad, min_theta_amplitude_rad);
  RequireAtLeast("BackboneOptions.num_points", num_points, 2);
}

BackboneSummary TraceBackbone(const HarmonicBalance& balance, const BackboneOptions& options,
                              const Eigen::VectorXcd& force_shape, const std::function<void(double)>& progress) {
  options.Validate();
  const int h = balance.num_harmonics();
  const int m = balance.num_unknowns();
  Eigen::VectorXcd shape = force_shape.size() ? PadHarmonics(force_shape, h) : PadHarmonics(Eigen::VectorXcd::Ones(2), h);
  shape[0] = force_shape.size() ? shape[0] : Complex(0.0);
  if (std::abs(shape[1] - 1.0) > 1e-12) throw std::invalid_argument("backbone: force_shape[1] must be 1");

  // Unknown vector u = [z without Re Θ_1, Im Θ_1; ω; F].
  auto assemble_z = [&](const Eigen::VectorXd& u, double amplitude) {
    Eigen::VectorXd z(m);
    z[0] = u[0];
    z[1] = 0.0;
    z[2] = -amplitude;
    z.tail(m - 3) = u.segment(1, m - 3);
    return z;
  };
  auto solve = [&](Eigen::VectorXd* u, double amplitude) {
    Eigen::VectorXd r, dr_domega;
    Eigen::MatrixXd jz;
    for (int iteration = 0; iteration < 40; ++iteration) {
      const double omega = (*u)[m - 2], force = (*u)[m - 1];
      const LinearHarmonics linear = balance.Linear(omega);
      // ∂R/∂ω is frozen after the first iterate (chord in ω): it costs a
      // second linear evaluation and changes little within one point.
      balance.Residual(assemble_z(*u, amplitude), linear, force * shape, &r, &jz,
                       iteration == 0 ? &dr_domega : nullptr);
      Eigen::MatrixXd j(m, m);
      j.col(0) = jz.col(0);
      j.middleCols(1, m - 3) = jz.rightCols(m - 3);
      j.col(m - 2) = dr_domega;
      Eigen::VectorXcd d_force(h + 1);
      for (int k = 0; k <= h; ++k) d_force[k] = -linear.blocked_moment_per_force[k] * shape[k];
      d_force[0] = d_force[0].real();
      j.col(m - 1) = HarmonicBalance::ToReal(d_force);
      // Scale: ω and F steps are judged relative to their own size.
      const Eigen::VectorXd step = j.partialPivLu().solve(-r);
      if (!step.allFinite()) return false;
      *u += step;
      Eigen::VectorXd relative = step;
      relative.head(m - 2) /= amplitude;
      relative[m - 2] /= omega;
      relative[m - 1] /= std::max(std::abs(force), 1e-12);
      if (relative.norm() < 1e-10 || r.norm() < 1e-14) return true;
    }
    return false;
  };

  BackboneSummary summary;
  // Start: the small-amplitude resonance of the beam with the law's initial stiffness.
  LinearBeamModel model = balance.beam().model();
  model.support_stiffness_Nm_rad = balance.law().InitialStiffness_Nm_rad();
  const double omega0 = LinearBeam(model, balance.beam().force_position_m()).NaturalFrequencies_rad_s(1)[0];
  Eigen::VectorXd u = Eigen::VectorXd::Zero(m);
  u[m - 2] = omega0;
  {
    const LinearHarmonics linear = balance.Linear(omega0);
    const Complex k_law(balance.law().InitialStiffness_Nm_rad(), omega0 * balance.law().InitialDamping_Nms_rad());
    const Complex theta_per_force = linear.blocked_moment_per_force[1] / (linear.rotational_stiffness[1] + k_law);
    u[m - 1] = options.min_theta_amplitude_rad / std::max(std::abs(theta_per_force), 1e-300);
  }
  Eigen::VectorXd previous_u;
  double previous_amplitude = 0.0;
  for (int i = 0; i < options.num_points; ++i) {
    const double fraction = static_cast<double>(i) / (options.num_points - 1);
    const double a0 = options.min_theta_amplitude_rad, a1 = options.max_theta_amplitude_rad;
    const double amplitude = options.geometric_spacing ? a0 * std::pow(a1 / a0, fraction) : a0 + (a1 - a0) * fraction;
    // Secant predictor in amplitude.
    Eigen::VectorXd guess = u;
    if (previous_u.size() == u.size() && i > 1)
      guess = u + (u - previous_u) * ((amplitude - summary.points.back().theta_amplitude_rad) /
                                      (summary.points.back().theta_amplitude_rad - previous_amplitude));
    if (!solve(&guess, amplitude)) {
      guess = u;
      if (!solve(&guess, amplitude)) {
        summary.message = "no phase-resonance solution at θ amplitude " + std::to_string(amplitude) + " rad";
        return summary;
      }
    }
    if (!summary.points.empty()) previous_amplitude = summary.points.back().theta_amplitude_rad;
    previous_u = u;
    u = guess;
    BackbonePoint point;
    point.theta_amplitude_rad = amplitude;
    point.omega_rad_s = u[m - 2];
    point.force_amplitude_N = u[m - 1];
    point.theta_rad = HarmonicBalance::ToComplex(assemble_z(u, amplitude));
    summary.points.push_back(std::move(point));
    if (progress) progress(fraction);
  }
  summary.complete = true;
  summary.message = "complete";
  return summary;
}

}  // namespace beamid::hb
