// The single-nonlinear-mode model of a structure's response near one isolated
// mode, fitted to first-harmonic points (frequency ω, inverse receptance
// G = F/X_d of force over displacement, amplitude a = |X_d|, s = a/a_ref):
//
//     A(a)·G = ω_n²(a) − ω² + 2i·ω·(ζω_n)(a),
//     ω_n²(a) = Σ_{j≤P} p_j·s^j        or, Iwan-like, p_0 + p_1·s^α,
//     (ζω_n)(a) = Σ_{j≤Q} q_j·s^j      or, Iwan-like, q_0 + q_1·s^β,
//     A(a) = A_0 + i·A_i (+ A_2·s²),
//
// with, optionally, the other modes' share R (real, [m/N]) taken off first:
// X_d/F = A(a)/D(a, ω) + R, a then the amplitude of the mode's own part
// |X_d − R·F|.
//
// A the modal constant (φ(x_sensor)·φ(x_force)/m). It is complex when the
// damping is not proportional (a localised damper makes the mode complex),
// and it changes with amplitude when the nonlinearity changes the mode's
// shape (a stiffening support restrains the rotation there): to first order
// by the square of the amplitude for a symmetric nonlinearity, hence A_2·s².
// The power laws are those of microslip joints (Iwan, Segalman: dissipation
// per cycle ∝ a^(2+β), softening ∝ a^α); their exponents are chosen on a grid
// by χ² and counted as parameters. For given exponents the model is linear
// in (A, p, q), so the fit is a weighted linear least-squares problem; each
// point's real/imaginary residual pair is whitened by the covariance of A·G
// from that of G (+ the frequency's variance on the real part), iterating A a
// few times. The parameter covariance is that estimator's (a sandwich) under
// every input's noise: where the amplitude carries noise (SingleModePoint) it
// moves A(a)·G − D(a, ω) through a too, by the backbone's slope, and that
// is not left out of the σ's (weighting by it instead, effective variance,
// runs away to steep backbones that excuse their own misfit). It is scaled
// by the reduced χ² against that noise when that exceeds 1 (the single mode
// is an approximation: residual modes, a shape changing with amplitude).
// Model choice between forms uses AICc with the noise scale left free,
// n·ln(χ²/n) + 2k + 2k(k+1)/(n−k−1), so it does not depend on how well the
// phasor uncertainties were estimated.
#pragma once

#include <complex>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace beamid::solver {

struct SingleModePoint {
  double omega_rad_s = 0.0;
  double omega_std_rad_s = 0.0;
  std::complex<double> inverse_receptance_N_m;  // G = F/X_d
  Eigen::Matrix2d inverse_receptance_covariance = Eigen::Matrix2d::Zero();  // of (Re G, Im G); 0 = unknown
  double amplitude_m = 0.0;                     // a = |X_d|
  // The amplitude is measured with the same noise as G (both from X_d): its
  // variance and its covariance with (Re G, Im G). Where ω_n² changes
  // steeply with a (a folding curve) that noise moves a point off the model
  // more than G's own does. 0: exact.
  double amplitude_variance_m2 = 0.0;
  Eigen::Vector2d amplitude_inverse_receptance_covariance = Eigen::Vector2d::Zero();
};

struct SingleModeFitOptions {
  int frequency_degree = 1;  // P (a power law has 2 terms: reported as 1)
  int damping_degree = 1;    // Q (likewise)
  // α, β > 0: the Iwan-like power law (two terms) instead of the polynomial.
  double frequency_exponent = 0.0;
  double damping_exponent = 0.0;
  // Whether A changes with amplitude (the A_2·s² term).
  bool amplitude_dependent_modal_constant = false;
  // R [m/N]: the other modes' share of the receptance, X_d/F = A/D + R
  // (0 = none); FitResidualReceptance estimates it. Counts as a parameter.
  double residual_receptance_m_N = 0.0;
  // a_ref: amplitudes are scaled by it to keep the problem well conditioned.
  double reference_amplitude_m = 1.0;
  // Points without a covariance are weighted with this relative standard
  // uncertainty of |G| (the χ² scaling then sets the real scale).
  double default_relative_std = 1e-2;
  int reweighting_iterations = 3;

  // Throws InputError naming the field, its value and the allowed range.
  void Validate() const;
};

class SingleModeFit {
 public:
  int frequency_degree = 0;
  int damping_degree = 0;
  double frequency_exponent = 0.0;  // α (> 0: power law)
  double damping_exponent = 0.0;    // β (> 0: power law)
  bool amplitude_dependent_modal_constant = false;
  double residual_receptance_m_N = 0.0;  // R: X_d/F = A/D + R
  // R's standard uncertainty when it was estimated (IncludeResidualUncertainty):
  // `covariance` then holds the parameters' change with R over it, and
  // `residual_covariance` their covariance with R (0: R taken as exact).
  double residual_receptance_std_m_N = 0.0;
  Eigen::VectorXd residual_covariance;
  // Searched outside the linear fit (exponents on a grid, R): each counts as
  // one more parameter in the AICc.
  int num_searched_parameters = 0;
  double reference_amplitude_m = 1.0;
  // Re A_0, Im A_0, [A_2,] then the terms of ω_n² (p), then those of ζω_n (q).
  Eigen::VectorXd parameters;
  Eigen::MatrixXd covariance;  // under every input's noise, scaled by max(1, noise_chi_square per dof)
  double chi_square = 0.0;
  // χ² against every input's noise (G's and the amplitude's): what scales the covariance.
  double noise_chi_square = 0.0;
  int num_residuals = 0;  // 2 per point
  double aicc = 0.0;
  // RMS over the points of A·Re G + ω² − ω_n²(a) [rad²/s²]: how far the
  // data stray from one nonlinear mode, in the units of ω_n².
  double backbone_residual_rms_rad2_s2 = 0.0;
  bool ok = false;        // false: too few points for the parameters

  int NumParameters() const { return static_cast<int>(parameters.size()) + num_searched_parameters; }
  double ReducedChiSquare() const;
  // Re A at zero amplitude.
  double ModalConstant() const { return parameters[0]; }
  std::complex<double> ModalConstantAt(double amplitude_m) const;
  // Covariance of (Re A(a), Im A(a)), and of those with R.
  Eigen::Matrix2d ModalConstantCovariance(double amplitude_m) const;
  Eigen::Vector2d ModalConstantResidualCovariance(double amplitude_m) const;
  // "polynomial 3" or "power 2.5" for ω_n² and ζω_n, and "A(a)" when A changes.
  std::string FormName() const;
  // The options that fit this form again (exponents fixed, R left at 0).
  SingleModeFitOptions Form() const;
  double NaturalFrequency_rad_s(double amplitude_m) const;
  double NaturalFrequencyStd_rad_s(double amplitude_m) const;
  double DampingRatio(double amplitude_m) const;
  double DampingRatioStd(double amplitude_m) const;
  // dζ/da and its standard uncertainty (delta method).
  double DampingSlope_per_m(double amplitude_m) const;
  double DampingSlopeStd_per_m(double amplitude_m) const;
  // D(a, ω) = ω_n²(a) − ω² + 2iω(ζω_n)(a), so X_d = A(a)·F/D.
  std::complex<double> DynamicTerm(double amplitude_m, double omega_rad_s) const;

  // The terms of ω_n² and ζω_n at an amplitude: 1, s, …, s^degree, or 1, s^exponent.
  Eigen::VectorXd FrequencyBasis(double amplitude_m) const;
  Eigen::VectorXd DampingBasis(double amplitude_m) const;
  int NumModalConstantTerms() const { return amplitude_dependent_modal_constant ? 3 : 2; }

 private:
  // Gradients of ω_n and ζ with respect to the parameters.
  Eigen::VectorXd NaturalFrequencyGradient(double amplitude_m) const;
  Eigen::VectorXd DampingGradient(double amplitude_m) const;
};

SingleModeFit FitSingleMode(const std::vector<SingleModePoint>& points, const SingleModeFitOptions& options);

// The R that minimises the fit's χ² for the form of `options`: residual
// (out-of-band) modes add a nearly constant, real receptance to the mode's,
// which bends the tails of each curve (the same way on both sides of the
// resonance) and, left out, biases A(a) and so the phase resonances. Searched
// within ±2 % of the largest |X_d/F| (a scan, then golden section); 0 when it
// does not lower the AICc (counted as one parameter more).
double FitResidualReceptance(const std::vector<SingleModePoint>& points, const SingleModeFitOptions& options);
// The one R of several groups of points (levels), each fitted with its own
// form and parameters: the other modes' share does not drift with the test's
// history, a mode's frequency may, and one backbone across levels that do
// not lie on one would hand its misfit to R.
double FitResidualReceptance(const std::vector<std::vector<SingleModePoint>>& groups,
                             const std::vector<SingleModeFitOptions>& forms);

// R's standard uncertainty from the curvature of the groups' summed χ² as
// R moves, each group's parameters refitted (the profile: Δχ² = 1 at 1σ),
// scaled by that χ²'s reduced value when it exceeds 1 (the χ² the search
// minimised, of G's noise alone: the amplitude's noise, and any misfit,
// show there). 0 for R = 0: the AICc left R out of the model.
double ResidualReceptanceStd(const std::vector<std::vector<SingleModePoint>>& groups,
                             const std::vector<SingleModeFitOptions>& forms, double residual);

// R estimated from the same points moves every parameter with it: the
// fit's covariance adds s·σ_R²·sᵀ, s = dx/dR (refitted at R ± h), and
// residual_covariance = s·σ_R². For R estimated jointly with the parameters
// that is the exact block inverse of the joint problem, to first order; the
// phase resonance reads A's covariance with R from it.
void IncludeResidualUncertainty(SingleModeFit& fit, const std::vector<SingleModePoint>& points, double residual_std);

// The power-law exponents tried for the Iwan-like forms.
std::vector<double> PowerLawExponentGrid();

// The best fit (smallest χ²) over the exponent grid for every power-law
// exponent that `options` asks for (any value > 0 there means "choose it"),
// each chosen exponent counted as a parameter.
SingleModeFit FitSingleModeChoosingExponents(const std::vector<SingleModePoint>& points,
                                             const SingleModeFitOptions& options);

}  // namespace beamid::solver
