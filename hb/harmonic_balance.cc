#include "hb/harmonic_balance.h"

#include <array>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/LU>

#include "hb/internal/real_fft.h"
#include "hb/matched_modal_loss.h"
#include "hb/option_checks.h"

namespace beamid::hb {
namespace {

// scale·D·S for a law's derivative matrix D over the samples (n × n) and a
// synthesis matrix S (n × (2H + 1)). The laws' D are sparse: diagonal for a
// memoryless law (the polynomial, the viscous term), and for the slider two
// entries per row (the sample itself and the one where it last stuck). With
// at most two terms per row, row i is scale·(d_ia·S_a + d_ib·S_b), which
// the dense product gives to the last bit (its other terms are exact
// zeros, and two terms sum alike in either order), in n·(2H + 1)
// operations instead of n²·(2H + 1).
Eigen::MatrixXd TimesSynthesis(const Eigen::MatrixXd& d, double scale, const Eigen::MatrixXd& synthesis) {
  const Eigen::Index n = d.rows();
  std::vector<std::array<Eigen::Index, 2>> nonzero(static_cast<std::size_t>(n), {-1, -1});
  std::vector<int> count(static_cast<std::size_t>(n), 0);
  bool sparse = true;
  for (Eigen::Index c = 0; c < d.cols() && sparse; ++c)
    for (Eigen::Index r = 0; r < n; ++r) {
      if (d(r, c) == 0.0) continue;
      int& k = count[static_cast<std::size_t>(r)];
      if (k == 2) {
        sparse = false;
        break;
      }
      nonzero[static_cast<std::size_t>(r)][static_cast<std::size_t>(k++)] = c;
    }
  if (!sparse) return scale == 1.0 ? Eigen::MatrixXd(d * synthesis) : Eigen::MatrixXd(scale * (d * synthesis));
  Eigen::MatrixXd out = Eigen::MatrixXd::Zero(n, synthesis.cols());
  for (Eigen::Index r = 0; r < n; ++r) {
    const auto [a, b] = nonzero[static_cast<std::size_t>(r)];
    if (a < 0) continue;
    if (b < 0)
      out.row(r) = scale * (d(r, a) * synthesis.row(a));
    else
      out.row(r) = scale * (d(r, a) * synthesis.row(a) + d(r, b) * synthesis.row(b));
  }
  return out;
}

int AutomaticSamples(int num_harmonics, bool smooth) {
  int n = 8;
  while (n < 4 * num_harmonics + 4) n *= 2;
  return smooth ? n : std::max(n, 256);
}

// Relative step of the difference quotient in ω of the linear part.
constexpr double kOmegaStep = 1e-7;

}  // namespace

Eigen::VectorXd HarmonicBalance::ToReal(const Eigen::VectorXcd& phasors) {
  const Eigen::Index h = phasors.size() - 1;
  Eigen::VectorXd z(2 * h + 1);
  z[0] = phasors[0].real();
  for (Eigen::Index k = 1; k <= h; ++k) {
    z[2 * k - 1] = phasors[k].real();
    z[2 * k] = phasors[k].imag();
  }
  return z;
}

Eigen::VectorXcd HarmonicBalance::ToComplex(const Eigen::VectorXd& z) {
  const Eigen::Index h = (z.size() - 1) / 2;
  Eigen::VectorXcd phasors(h + 1);
  phasors[0] = z[0];
  for (Eigen::Index k = 1; k <= h; ++k) phasors[k] = Complex(z[2 * k - 1], z[2 * k]);
  return phasors;
}

Eigen::VectorXcd PadHarmonics(const Eigen::VectorXcd& phasors, int num_harmonics) {
  Eigen::VectorXcd out = Eigen::VectorXcd::Zero(num_harmonics + 1);
  const Eigen::Index count = std::min<Eigen::Index>(phasors.size(), num_harmonics + 1);
  out.head(count) = phasors.head(count);
  return out;
}

void HarmonicBalanceOptions::Validate() const {
  using namespace option_checks;
  RequireInRange("HarmonicBalanceOptions.num_harmonics", num_harmonics, 1, kMaxHarmonics);
  // Fewer than 2H + 2 samples cannot carry H harmonics (Nyquist).
  if (num_time_samples != 0)
    RequireAtLeast("HarmonicBalanceOptions.num_time_samples (0: automatic)", num_time_samples, 2 * num_harmonics + 2);
  RequirePositive("HarmonicBalanceOptions.tolerance", tolerance);
  RequireAtLeast("HarmonicBalanceOptions.max_iterations", max_iterations, 1);
}

HarmonicBalance::HarmonicBalance(const LinearBeam& beam, const SupportLaw& law, const HarmonicBalanceOptions& options)
    : beam_(beam), law_(law.Clone()), options_(options) {
  options_.Validate();
  num_time_samples_ = options_.num_time_samples > 0
                          ? options_.num_time_samples
                          : AutomaticSamples(options_.num_harmonics, law_->IsSmooth());
  if (num_time_samples_ < 2 * options_.num_harmonics + 2)
    throw std::invalid_argument("num_time_samples must be at least 2H + 2 = " +
                                std::to_string(2 * options_.num_harmonics + 2));
  fft_ = std::make_unique<internal::RealFft>(num_time_samples_);
  const int n = num_time_samples_, h = options_.num_harmonics;
  synthesis_.resize(n, 2 * h + 1);
  synthesis_rate_.resize(n, 2 * h + 1);
  analysis_.resize(2 * h + 1, n);
  for (int i = 0; i < n; ++i) {
    synthesis_(i, 0) = 1.0;
    synthesis_rate_(i, 0) = 0.0;
    analysis_(0, i) = 1.0 / n;
    for (int k = 1; k <= h; ++k) {
      const double phase = 2.0 * std::numbers::pi * k * i / n;
      const double c = std::cos(phase), s = std::sin(phase);
      // θ = Re((a + ib) e^{iφ}) = a cos φ − b sin φ;  θ̇/ω = k(−a sin φ − b cos φ)
      synthesis_(i, 2 * k - 1) = c;
      synthesis_(i, 2 * k) = -s;
      synthesis_rate_(i, 2 * k - 1) = -k * s;
      synthesis_rate_(i, 2 * k) = -k * c;
      analysis_(2 * k - 1, i) = 2.0 * c / n;
      analysis_(2 * k, i) = -2.0 * s / n;
    }
  }
}

HarmonicBalance::~HarmonicBalance() = default;
HarmonicBalance::HarmonicBalance(HarmonicBalance&&) noexcept = default;

LinearHarmonics ComputeLinearHarmonics(const LinearBeam& beam, double omega_rad_s, int num_harmonics,
                                       const std::vector<double>& positions_m) {
  const int h = num_harmonics;
  const auto count = static_cast<Eigen::Index>(positions_m.size());
  LinearHarmonics linear;
  linear.omega_rad_s = omega_rad_s;
  linear.rotational_stiffness.resize(h + 1);
  linear.blocked_moment_per_force.resize(h + 1);
  linear.displacement_per_force.resize(count, h + 1);
  linear.displacement_per_rotation.resize(count, h + 1);
  const MatchedModalLoss* modal_loss = beam.matched_modal_loss();
  MatchedModalLoss::ModeValues modes;
  if (modal_loss) modes = modal_loss->At(positions_m);
  for (int k = 0; k <= h; ++k) {
    auto c = beam.CondenseOnSupportRotation(k * omega_rad_s, positions_m);
    if (modal_loss && k > 0) modal_loss->Correct(modes, omega_rad_s, k, &c);
    const bool real = k == 0;
    auto part = [real](Complex v) { return real ? Complex(v.real()) : v; };
    linear.rotational_stiffness[k] = part(c.rotational_stiffness_Nm_rad);
    linear.blocked_moment_per_force[k] = part(c.blocked_moment_per_force_m);
    for (Eigen::Index i = 0; i < count; ++i) {
      linear.displacement_per_force(i, k) = part(c.displacement_per_force_m_N[i]);
      linear.displacement_per_rotation(i, k) = part(c.displacement_per_rotation_m[i]);
    }
  }
  return linear;
}

LinearHarmonics HarmonicBalance::Linear(double omega_rad_s) const {
  return ComputeLinearHarmonics(beam_, omega_rad_s, options_.num_harmonics);
}

void HarmonicBalance::Residual(const Eigen::VectorXd& z, const LinearHarmonics& linear,
                               const Eigen::VectorXcd& force_N, Eigen::VectorXd* residual,
                               Eigen::MatrixXd* d_residual_d_z, Eigen::VectorXd* d_residual_d_omega) const {
  const int h = options_.num_harmonics;
  const double omega = linear.omega_rad_s;
  const Eigen::VectorXcd theta = ToComplex(z);
  const Eigen::VectorXcd force = PadHarmonics(force_N, h);

  Eigen::VectorXcd moment_phasors;
  const PeriodicMoment moment = AlternateFrequencyTime(theta, omega, &moment_phasors);

  Eigen::VectorXcd r(h + 1);
  for (int k = 0; k <= h; ++k)
    r[k] = linear.rotational_stiffness[k] * theta[k] + moment_phasors[k] -
           linear.blocked_moment_per_force[k] * force[k];
  r[0] = r[0].real();
  *residual = ToReal(r);

  if (d_residual_d_z) {
    Eigen::MatrixXd& j = *d_residual_d_z;
    j = analysis_ * (TimesSynthesis(moment.d_moment_d_theta, 1.0, synthesis_) +
                     TimesSynthesis(moment.d_moment_d_theta_rate, omega, synthesis_rate_));
    j(0, 0) += linear.rotational_stiffness[0].real();
    for (int k = 1; k <= h; ++k) {
      const Complex d = linear.rotational_stiffness[k];
      j(2 * k - 1, 2 * k - 1) += d.real();
      j(2 * k - 1, 2 * k) -= d.imag();
      j(2 * k, 2 * k - 1) += d.imag();
      j(2 * k, 2 * k) += d.real();
    }
  }
  if (d_residual_d_omega) {
    // Forward difference: one extra linear evaluation; its O(h) error (~1e-6
    // relative) only slows Newton's last digits, never its answer.
    const double step = kOmegaStep * std::max(omega, 1.0);
    const LinearHarmonics up = Linear(omega + step);
    Eigen::VectorXcd dr(h + 1);
    for (int k = 0; k <= h; ++k)
      dr[k] = (up.rotational_stiffness[k] - linear.rotational_stiffness[k]) / step * theta[k] -
              (up.blocked_moment_per_force[k] - linear.blocked_moment_per_force[k]) / step * force[k];
    dr[0] = 0.0;
    *d_residual_d_omega = ToReal(dr) + analysis_ * (moment.d_moment_d_theta_rate * (synthesis_rate_ * z));
  }
}

Eigen::MatrixXd HarmonicBalance::ParameterJacobian(const Eigen::VectorXd& z, double omega_rad_s) const {
  const Eigen::VectorXd theta_t = synthesis_ * z;
  const Eigen::VectorXd theta_rate_t = omega_rad_s * (synthesis_rate_ * z);
  return analysis_ * law_->PeriodicParameterJacobian(theta_t, theta_rate_t);
}

HarmonicBalanceSolution HarmonicBalance::Solve(double omega_rad_s, const Eigen::VectorXcd& force_N,
                                               const Eigen::VectorXd& initial) const {
  const LinearHarmonics linear = Linear(omega_rad_s);
  const int h = options_.num_harmonics;
  Eigen::VectorXd z;
  if (initial.size() == num_unknowns()) {
    z = initial;
  } else {
    // The linear solution with the law's small-amplitude stiffness and damping.
    const Eigen::VectorXcd force = PadHarmonics(force_N, h);
    Eigen::VectorXcd theta(h + 1);
    for (int k = 0; k <= h; ++k)
      theta[k] = linear.blocked_moment_per_force[k] * force[k] /
                 (linear.rotational_stiffness[k] +
                  Complex(law_->InitialStiffness_Nm_rad(), k * omega_rad_s * law_->InitialDamping_Nms_rad()));
    z = ToReal(theta);
  }
  HarmonicBalanceSolution solution;
  solution.omega_rad_s = omega_rad_s;
  Eigen::VectorXd r;
  Eigen::MatrixXd j;
  for (int iteration = 1; iteration <= options_.max_iterations; ++iteration) {
    Residual(z, linear, force_N, &r, &j);
    const Eigen::VectorXd step = j.partialPivLu().solve(-r);
    if (!step.allFinite()) break;
    z += step;
    solution.iterations = iteration;
    if (step.norm() <= options_.tolerance * (z.norm() + 1e-12)) {
      solution.converged = true;
      break;
    }
  }
  Residual(z, linear, force_N, &r);
  solution.residual_norm_Nm = r.norm();
  solution.theta_rad = ToComplex(z);
  return solution;
}

Eigen::MatrixXcd HarmonicBalance::Displacements(const HarmonicBalanceSolution& solution,
                                                const Eigen::VectorXcd& force_N,
                                                const std::vector<double>& positions_m) const {
  const int h = options_.num_harmonics;
  const LinearHarmonics linear = ComputeLinearHarmonics(beam_, solution.omega_rad_s, h, positions_m);
  const Eigen::VectorXcd force = PadHarmonics(force_N, h);
  return linear.displacement_per_force * force.asDiagonal() +
         linear.displacement_per_rotation * solution.theta_rad.asDiagonal();
}

Eigen::VectorXcd HarmonicBalance::SupportMoment(const HarmonicBalanceSolution& solution) const {
  Eigen::VectorXcd moment;
  AlternateFrequencyTime(solution.theta_rad, solution.omega_rad_s, &moment);
  return moment;
}

// θ_k → θ(t_n), θ̇(t_n) → M(t_n) → M_k.
PeriodicMoment HarmonicBalance::AlternateFrequencyTime(const Eigen::VectorXcd& theta, double omega_rad_s,
                                                       Eigen::VectorXcd* moment_phasors) const {
  const int h = options_.num_harmonics;
  Eigen::VectorXd theta_t, theta_rate_t;
  fft_->Inverse(theta, &theta_t);
  Eigen::VectorXcd rate_phasors(h + 1);
  for (int k = 0; k <= h; ++k) rate_phasors[k] = Complex(0.0, k * omega_rad_s) * theta[k];
  fft_->Inverse(rate_phasors, &theta_rate_t);
  PeriodicMoment moment = law_->EvaluatePeriodic(theta_t, theta_rate_t);
  fft_->Forward(moment.moment_Nm, h, moment_phasors);
  return moment;
}

}  // namespace beamid::hb
