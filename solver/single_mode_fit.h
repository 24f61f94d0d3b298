// The single-nonlinear-mode model of a structure's response near one isolated
// mode, fitted to first-harmonic points (frequency ω, inverse receptance
// G = F/X_d of force over displacement, amplitude a = |X_d|):
//
//     A·G = ω_n²(a) − ω² + 2i·ω·(ζω_n)(a),
//     ω_n²(a) = Σ_{j≤P} p_j·(a/a_ref)^j,   (ζω_n)(a) = Σ_{j≤Q} q_j·(a/a_ref)^j,
//
// A the modal constant (φ(x_sensor)·φ(x_force)/m, signed). The model is linear
// in (A, p, q), so the fit is a weighted linear least-squares problem; each
// point's real/imaginary residual pair is whitened by A²·Cov(G) (+ the
// frequency's variance on the real part), iterating A a few times. The
// parameter covariance is scaled by the reduced χ² when that exceeds 1 (the
// single mode is an approximation: residual modes, amplitude errors).
// Model choice between degrees (P, Q) uses AICc with the noise scale left
// free, n·ln(χ²/n) + 2k + 2k(k+1)/(n−k−1), so it does not depend on how
// well the phasor uncertainties were estimated.
#pragma once

#include <complex>
#include <vector>

#include <Eigen/Core>

namespace beamid::solver {

struct SingleModePoint {
  double omega_rad_s = 0.0;
  double omega_std_rad_s = 0.0;
  std::complex<double> inverse_receptance_N_m;  // G = F/X_d
  Eigen::Matrix2d inverse_receptance_covariance = Eigen::Matrix2d::Zero();  // of (Re G, Im G); 0 = unknown
  double amplitude_m = 0.0;                     // a = |X_d|
};

struct SingleModeFitOptions {
  int frequency_degree = 1;  // P
  int damping_degree = 1;    // Q
  // a_ref: amplitudes are scaled by it to keep the problem well conditioned.
  double reference_amplitude_m = 1.0;
  // Points without a covariance are weighted with this relative standard
  // uncertainty of |G| (the χ² scaling then sets the real scale).
  double default_relative_std = 1e-2;
  int reweighting_iterations = 3;
};

class SingleModeFit {
 public:
  int frequency_degree = 0;
  int damping_degree = 0;
  double reference_amplitude_m = 1.0;
  Eigen::VectorXd parameters;  // A, p_0..p_P, q_0..q_Q
  Eigen::MatrixXd covariance;  // scaled by max(1, reduced χ²)
  double chi_square = 0.0;
  int num_residuals = 0;  // 2 per point
  double aicc = 0.0;
  // RMS over the points of A·Re G + ω² − ω_n²(a) [rad²/s²]: how far the
  // data stray from one nonlinear mode, in the units of ω_n².
  double backbone_residual_rms_rad2_s2 = 0.0;
  bool ok = false;        // false: too few points for the parameters

  int NumParameters() const { return static_cast<int>(parameters.size()); }
  double ReducedChiSquare() const;
  double ModalConstant() const { return parameters[0]; }
  double NaturalFrequency_rad_s(double amplitude_m) const;
  double NaturalFrequencyStd_rad_s(double amplitude_m) const;
  double DampingRatio(double amplitude_m) const;
  double DampingRatioStd(double amplitude_m) const;
  // dζ/da and its standard uncertainty (delta method).
  double DampingSlope_per_m(double amplitude_m) const;
  double DampingSlopeStd_per_m(double amplitude_m) const;
  // D(a, ω) = ω_n²(a) − ω² + 2iω(ζω_n)(a), so X_d = A·F/D.
  std::complex<double> DynamicTerm(double amplitude_m, double omega_rad_s) const;

  // 1, a/a_ref, …, (a/a_ref)^degree.
  Eigen::VectorXd Basis(double amplitude_m, int degree) const;

 private:
  // Gradients of ω_n and ζ with respect to the parameters.
  Eigen::VectorXd NaturalFrequencyGradient(double amplitude_m) const;
  Eigen::VectorXd DampingGradient(double amplitude_m) const;
};

SingleModeFit FitSingleMode(const std::vector<SingleModePoint>& points, const SingleModeFitOptions& options);

}  // namespace beamid::solver
