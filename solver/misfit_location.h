// Where a fitted model misses the recordings. The standardised residual of
// channel c, harmonic k, step i is the 2-vector
//     r = L⁻¹ (Y_model − Y_measured),   L Lᵀ = Cov(Re Y, Im Y)   (solver/fit_data.h),
// N(0, I) when the model is right. Its squares are summed over groups (a
// channel, a harmonic, a level, a band of the response curve, a part of the
// phasor) and each group's sum is tested against χ²(2·pairs) (one dof per
// part). The groups are tested together at a family-wise significance
// (Holm over every group tested), so a correct model raises no alarm.
//
// Parts of a residual pair, in the whitened plane: the unit direction u of
// the phasor a change of stiffness would move the response along,
//     fundamental:  δY ∝ Y·(Y/F₁)    (one mode: δY = −Y·H·δk, H = Y/F real
//                                     below resonance, −i/(cω) at it),
//     harmonic k≥2: δY ∝ Y_k          (the model's own harmonic),
// whitened (u = L⁻¹[Re, Im] normalised): "in_phase" = (u·r)², stiffness-like;
// "quadrature" = |r|² − (u·r)², dissipation-like (the same change rotated by
// 90°, as a change of damping moves the response). Where the model's phasor
// is below the noise (|L⁻¹Y| < 3) the direction is undefined and the pair
// counts in "both" only.
//
// Near resonance: steps of a level whose measured fundamental on that channel
// is at least 1/√2 of the level's largest (the measured half-power band).
//
// The support's loop (LoopEvidence): θ_k and M_k per step from
// ReconstructSupport (measured phasors, exact linear beam). Energy the
// support dissipates per cycle,
//     W = ∮ M dθ = π Σ_k k·Im(M_k·conj Θ_k),
// against the viscous ellipse π·c·ω·|Θ₁|² of the reference model's c. A
// viscous support keeps c_eq = W/(π ω |Θ₁|²) constant (W ∝ |Θ₁|²); friction
// makes it depend on amplitude.
#pragma once

#include <limits>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include "hb/linear_beam.h"
#include "solver/fit_data.h"

namespace beamid::solver {

struct MisfitLocationOptions {
  // Family-wise significance: the probability that a correct model has any
  // group flagged (Holm–Bonferroni over all groups tested).
  double family_significance = 0.01;
  // Parameters fitted to these residuals; subtracted from the overall test's
  // dof (the group tests ignore them, which makes them slightly conservative).
  int num_fitted_parameters = 0;
  // A group's excess χ² share must reach this to be named in a finding.
  double finding_min_share = 0.05;
  // Reconstruct the support's loops (needs the exact linear beam per step).
  bool analyse_loops = true;
  // Relative error of the loops beyond the phasor noise, added in quadrature
  // to σ(c_eq) and to σ of each part of M̃_k: the exact linear beam is not
  // the real one (its damping law, the sensors' attachment), which biases W
  // by ~1 % on simulated campaigns; real rigs are worse.
  double loop_relative_model_error = 0.03;
};

// One tested group of standardised residuals.
struct MisfitGroupTest {
  std::string channel;          // "" = all channels
  int harmonic = 0;             // 0 = all harmonics
  std::string level;            // "" = all levels
  std::string part = "both";    // "in_phase" | "quadrature" | "both"
  std::string band = "all";     // "near_resonance" | "away" | "all"
  double chi2 = 0.0;            // Σ|r|² (or its part)
  int dof = 0;                  // 2 per pair for "both", 1 per pair for a part
  double p_value = 1.0;         // P(χ²(dof) ≥ chi2)
  double adjusted_p_value = 1.0;  // Holm-adjusted over the family
  bool significant = false;     // adjusted_p_value < family_significance
  double excess_chi2 = 0.0;     // max(chi2 − dof, 0): the misfit beyond noise
  // Slope of log(misfit amplitude beyond noise) vs log(response amplitude)
  // over the levels (see MisfitLocation::level_growth_exponent); NaN when
  // fewer than two levels show misfit or the group is one level.
  double growth_exponent = std::numeric_limits<double>::quiet_NaN();
};

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

struct MisfitLocation {
  // All residuals together (dof reduced by the fitted parameters).
  double chi2 = 0.0;
  int dof = 0;
  double p_value = 1.0;
  bool significant = false;        // overall test, or any group, at the family significance
  int num_groups_tested = 0;
  std::vector<MisfitGroupTest> groups;  // every group tested, in a fixed order

  // Signature features, shares of the excess χ² (Σ max(χ²_g − dof_g, 0) over
  // the groups of one breakdown), 0 when there is no excess:
  double in_phase_fraction = 0.0;        // in_phase / (in_phase + quadrature), channel×harmonic×part groups
  double near_resonance_fraction = 0.0;  // near_resonance / (near + away), channel×harmonic×band groups
  double fundamental_fraction = 0.0;     // harmonic 1 / all harmonics, channel×harmonic groups
  double even_harmonic_fraction = 0.0;   // harmonics 2, 4 / all
  double beyond_fitted_fraction = 0.0;   // harmonics > fitted_harmonics / all
  std::vector<double> harmonic_excess_chi2;  // [k−1], over all channels
  std::vector<double> channel_excess_chi2;   // [c] in data.channels order
  // Slope of log A_l vs log R_l over the levels l, where
  //   A_l = sqrt(Σ max(|e|²/σ_c² − 2σ²/σ_c², 0)/n_l)  the misfit beyond noise,
  //   R_l = sqrt(Σ |Y_c1|²/σ_c² / n_l)                the measured response,
  // e = Y_model − Y_measured, σ_c the channel's median σ (a level-independent
  // scale). 1: the misfit scales like the response (a linear error); > 1 it
  // grows faster (a nonlinearity the model lacks); ≈ 0 it does not grow.
  // NaN with fewer than two levels showing misfit.
  double level_growth_exponent = std::numeric_limits<double>::quiet_NaN();
  std::vector<double> level_misfit_amplitude;   // A_l, data.levels order
  std::vector<double> level_response_amplitude; // R_l

  LoopEvidence loops;
  // Plain sentences for a test engineer.
  std::vector<std::string> findings;
};

// data: measured phasors (any num_fit_harmonics, e.g. 5, every channel to be
// examined). model: per step a channels × K' matrix of the fitted model's
// phasors in FitStep::measured's layout and units (K' ≤ K; missing columns
// and harmonics the model lacks are 0). fitted_harmonics: the harmonics
// 1..fitted_harmonics the model fitted. reference_beam: the exact linear beam
// of the fitted model (its c is the loop's viscous reference; k1 and c are
// not used in the reconstruction itself).
// Throws std::invalid_argument when model and data disagree in size.
MisfitLocation LocateMisfit(const FitData& data, const std::vector<Eigen::MatrixXcd>& model, int fitted_harmonics,
                            const hb::LinearBeamModel& reference_beam, const MisfitLocationOptions& options = {});

// The support's loops alone (also part of LocateMisfit).
LoopEvidence AnalyseSupportLoops(const FitData& data, const hb::LinearBeamModel& reference_beam,
                                 double family_significance = 0.01, double relative_model_error = 0.03);

nlohmann::json ToJson(const MisfitLocation& location);
nlohmann::json ToJson(const LoopEvidence& loops);

}  // namespace beamid::solver
