// Exact harmonic balance of the continuous beam with a nonlinear support.
//
// The nonlinearity acts only on θ = y'(L), so the unknowns are the phasors
// Θ_0..Θ_H of θ (docs/fourier-convention.md). The beam is exact (no modes):
// condensed on θ it gives, for each harmonic k at frequency kω,
//     R_k = D(kω)·Θ_k + M_k(Θ) − B(kω)·F_k = 0,          k = 0..H,
// with D, B from LinearBeam::CondenseOnSupportRotation (Krack & Gross's
// HB_residual in our notation: the linear dynamic stiffness times the
// harmonics, plus the nonlinear force harmonics, minus the excitation).
// M_k are the harmonics of the support moment M(θ(t), θ̇(t)) computed by
// alternating frequency–time: inverse FFT of Θ to N samples of one period,
// the support law on the samples, forward FFT back (FFTW plans). The force
// may hold harmonics F_0..F_H (a measured force is never a pure sine).
// The real unknown vector is z = [Θ_0, Re Θ_1, Im Θ_1, …, Re Θ_H, Im Θ_H].
//
// A HarmonicBalance object owns FFT buffers: use one per thread.
#pragma once

#include <memory>
#include <span>
#include <vector>

#include <Eigen/Core>

#include "hb/linear_beam.h"
#include "hb/support_law.h"

namespace beamid::hb {

namespace internal {
class RealFft;
}

struct HarmonicBalanceOptions {
  // H: highest harmonic kept.
  int num_harmonics = 7;
  // N: time samples per period for the alternating frequency–time step.
  // 0 = automatic: the smallest power of two ≥ 4H + 4 (alias-free for cubic
  // laws) for smooth laws, and at least 256 for laws with corners
  // (SupportLaw::IsSmooth: slip, a one-sided contact), whose harmonics
  // decay slowly and alias (a one-sided stiffness sampled 32 times per
  // period biased an identified k_a by 4 %).
  int num_time_samples = 0;
  // Newton stops when the step is below tolerance × (|z| + 1e-12 rad).
  double tolerance = 1e-10;
  int max_iterations = 40;

  // Throws InputError naming the field, its value and the allowed range.
  void Validate() const;
};

// The beam's linear part at the harmonics of one fundamental frequency.
struct LinearHarmonics {
  double omega_rad_s = 0.0;
  Eigen::VectorXcd rotational_stiffness;   // D(kω), k = 0..H
  Eigen::VectorXcd blocked_moment_per_force;  // B(kω)
  // Optional, positions × (H + 1): displacement = a·F_k + b·Θ_k.
  Eigen::MatrixXcd displacement_per_force;     // a_x(kω) [m/N]
  Eigen::MatrixXcd displacement_per_rotation;  // b_x(kω) [m/rad]
};

// The linear part of `beam` at the harmonics 0..H of ω (static terms real:
// a static load has no structural damping), and the transfer to positions.
LinearHarmonics ComputeLinearHarmonics(const LinearBeam& beam, double omega_rad_s, int num_harmonics,
                                       const std::vector<double>& positions_m = {});

struct HarmonicBalanceSolution {
  double omega_rad_s = 0.0;
  Eigen::VectorXcd theta_rad;  // Θ_0..Θ_H
  bool converged = false;
  int iterations = 0;
  double residual_norm_Nm = 0.0;
};

class HarmonicBalance {
 public:
  HarmonicBalance(const LinearBeam& beam, const SupportLaw& law, const HarmonicBalanceOptions& options = {});
  ~HarmonicBalance();
  HarmonicBalance(HarmonicBalance&&) noexcept;
  HarmonicBalance(const HarmonicBalance&) = delete;
  HarmonicBalance& operator=(const HarmonicBalance&) = delete;

  int num_harmonics() const { return options_.num_harmonics; }
  int num_unknowns() const { return 2 * options_.num_harmonics + 1; }
  int num_time_samples() const { return num_time_samples_; }
  const LinearBeam& beam() const { return beam_; }
  const SupportLaw& law() const { return *law_; }

  LinearHarmonics Linear(double omega_rad_s) const;

  // R(z) and, when asked, ∂R/∂z and ∂R/∂ω (the latter by a forward
  // difference of the linear part, which is smooth in ω, plus the exact θ̇ term).
  void Residual(const Eigen::VectorXd& z, const LinearHarmonics& linear, const Eigen::VectorXcd& force_N,
                Eigen::VectorXd* residual, Eigen::MatrixXd* d_residual_d_z = nullptr,
                Eigen::VectorXd* d_residual_d_omega = nullptr) const;

  // ∂R/∂p: derivatives of the residual with respect to the support law's
  // parameters (SupportLaw::Parameters() order), (2H+1) × P.
  Eigen::MatrixXd ParameterJacobian(const Eigen::VectorXd& z, double omega_rad_s) const;
  // Changes the law's parameters (identification); order as Parameters().
  void SetLawParameters(std::span<const double> values) { law_->SetParameterValues(values); }

  // Newton from `initial` (z layout; empty = the linear solution).
  HarmonicBalanceSolution Solve(double omega_rad_s, const Eigen::VectorXcd& force_N,
                                const Eigen::VectorXd& initial = {}) const;

  // Displacement phasors Y_0..Y_H [m] at each position (rows) for a solution.
  Eigen::MatrixXcd Displacements(const HarmonicBalanceSolution& solution, const Eigen::VectorXcd& force_N,
                                 const std::vector<double>& positions_m) const;

  // Support moment phasors M_0..M_H [N·m] on a solution's θ.
  Eigen::VectorXcd SupportMoment(const HarmonicBalanceSolution& solution) const;

  static Eigen::VectorXd ToReal(const Eigen::VectorXcd& phasors);
  static Eigen::VectorXcd ToComplex(const Eigen::VectorXd& z);

 private:
  PeriodicMoment AlternateFrequencyTime(const Eigen::VectorXcd& theta_rad, double omega_rad_s,
                                        Eigen::VectorXcd* moment_phasors) const;

  LinearBeam beam_;
  std::unique_ptr<SupportLaw> law_;
  HarmonicBalanceOptions options_;
  int num_time_samples_ = 0;
  std::unique_ptr<internal::RealFft> fft_;
  // AFT matrices for the Jacobian: samples = E·z, (d/dt samples) = ω·E_rate·z,
  // phasors (real layout) = P·samples.
  Eigen::MatrixXd synthesis_, synthesis_rate_, analysis_;
};

// Extends a force phasor vector to H + 1 entries (missing harmonics are 0).
Eigen::VectorXcd PadHarmonics(const Eigen::VectorXcd& phasors, int num_harmonics);

}  // namespace beamid::hb
