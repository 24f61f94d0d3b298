// The support's moment–rotation loops, reconstructed at every step from the
// measured phasors through the exact linear beam (ReconstructSupport in
// solver/support_reconstruction.h gives Θ_k and M_k). Energy the support
// dissipates per cycle,
//     W = ∮ M dθ = π Σ_k k·Im(M_k·conj Θ_k),
// against the viscous ellipse π·c·ω·|Θ₁|² of the reference model's c. A
// viscous support keeps c_eq = W/(π ω |Θ₁|²) constant (W ∝ |Θ₁|²); friction
// makes it depend on amplitude. Even harmonics of θ point at asymmetry.
#pragma once

#include <limits>
#include <string>
#include <vector>


#include "hb/linear_beam.h"
#include "solver/estimation/fit_data.h"

namespace beamid::solver {

// The support's moment–rotation loop at one step. For k ≥ 2 the moment the
// reference model's linear support does not explain,
//     M̃_k = M_k − (k1 + i·k·ω·c)·Θ_k,   σ(M̃_k) = |D(kω) + k1 + i·k·ω·c|·σ(Θ_k),
// is split against e^{ik·arg Θ₁}: a conservative law M(θ) of a harmonic θ
// gives M̃_k in phase with it ("elastic"); a hysteretic one (friction) also
// gives a part in quadrature ("hysteretic").
struct LoopStep {
  std::string level;
  double omega_rad_s = 0.0;
  double theta_amplitude_rad = 0.0;        // |Θ₁|
  double theta_std_rad = 0.0;              // σ of Re Θ₁ and of Im Θ₁
  double moment_amplitude_Nm = 0.0;        // |M₁|
  double dissipated_energy_J = 0.0;        // W = π Σ_k k·Im(M_k conj Θ_k)
  double dissipated_energy_std_J = 0.0;    // its 1σ: phasor uncertainties and model error
  double viscous_energy_J = 0.0;           // π·c·ω·|Θ₁|², c of the reference model
  double equivalent_damping_Nms_rad = 0.0; // W / (π ω |Θ₁|²)
  double equivalent_damping_std_Nms_rad = 0.0;  // likewise
  // sqrt(Σ_{k≥2}|M̃_k|²)/|M₁|: 0 for an ellipse of a linear support.
  double moment_harmonic_ratio = 0.0;
  // Σ_{k≥2} of the squared standardised parts of M̃_k (1 dof each).
  double elastic_harmonic_chi2 = 0.0;
  double hysteretic_harmonic_chi2 = 0.0;
  int harmonic_dof = 0;                    // per part
  // sqrt(Σ_{k even}|X_k|²)/sqrt(Σ_k |X_k|²) of θ and of M.
  double theta_even_fraction = 0.0;
  double moment_even_fraction = 0.0;
};

struct LoopEvidence {
  std::vector<LoopStep> steps;
  // Steps whose |Θ₁| is at least 10 σ: the loop statistics use only these.
  int num_steps_used = 0;
  // Weighted slope of log(W/ω) vs log|Θ₁| over the used steps whose W is at
  // least 3σ: 2 for a viscous support, steeper where friction starts to
  // slip. NaN with fewer than 3 such steps.
  double area_exponent = std::numeric_limits<double>::quiet_NaN();
  double area_exponent_std = std::numeric_limits<double>::quiet_NaN();
  // Test of "c_eq is the same at every used step" (viscous): χ² of the
  // steps' c_eq about their weighted mean, dof = steps − 1, p-value.
  double viscous_chi2 = 0.0;
  int viscous_dof = 0;
  double viscous_p_value = 1.0;
  double mean_equivalent_damping_Nms_rad = 0.0;  // the weighted mean
  // c_eq at the largest-amplitude used step over c_eq at the smallest
  // (1 for viscous).
  double damping_ratio_high_to_low = std::numeric_limits<double>::quiet_NaN();
  // M̃_k, k ≥ 2, over the used steps: χ² of its elastic and hysteretic parts.
  double elastic_harmonic_chi2 = 0.0;
  double hysteretic_harmonic_chi2 = 0.0;
  int harmonic_dof = 0;
  double elastic_harmonic_p_value = 1.0;
  double hysteretic_harmonic_p_value = 1.0;
  double max_moment_harmonic_ratio = 0.0;
  // Even harmonics of θ: χ² of Θ_2, Θ_4 against 0 over the used steps.
  double theta_even_chi2 = 0.0;
  int theta_even_dof = 0;
  double theta_even_p_value = 1.0;
  // Each at the family significance (Bonferroni over these four tests):
  bool dissipation_not_viscous = false;  // viscous test rejected
  bool non_elliptic = false;             // elastic or hysteretic part of M̃_k significant
  bool hysteretic_shape = false;         // hysteretic part of M̃_k significant
  bool asymmetric = false;               // even harmonics of θ significant
};

// From the measured phasors of `data` (all its channels and harmonics) and
// the exact linear beam of the reference model (its k1 and c are the linear
// support M̃_k and the viscous energy refer to). Statistics at the family
// significance, Bonferroni over the four tests.
LoopEvidence AnalyseSupportLoops(const FitData& data, const hb::LinearBeamModel& reference_beam,
                                 double family_significance = 0.01, double relative_model_error = 0.03);

}  // namespace beamid::solver
