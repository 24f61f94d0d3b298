// Where a fitted model misses the recordings. The standardised residual of
// channel c, harmonic k, step i is the 2-vector
//     r = L⁻¹ (Y_model − Y_measured),
//     L Lᵀ = Cov(Re Y, Im Y) + (ε·|Y_model,c1|)²·I   (solver/fit_data.h; ε: the
//            model's own error, MisfitLocationOptions::model_relative_error),
// N(0, I) when the model is right. Its squares are summed over groups and
// each group's sum is tested against χ²(2·pairs) (one dof per pair for a
// part). The groups, per channel c and harmonic k = 1..K of the data:
//     c×k (all levels, both parts); c×k×part (in_phase, quadrature);
//     c×k×level; c×k×band (near_resonance, away);
// plus the overall test of all residuals. They are tested together at a
// family-wise significance (Holm's step-down over every test, valid under
// any dependence), so a correct model raises no alarm more often than that.
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
// The support's loops (solver/support_loops.h) are part of the location.
#pragma once

#include <limits>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "hb/json_schema.h"
#include "hb/linear_beam.h"
#include "solver/estimation/fit_data.h"
#include "solver/diagnosis/support_loops.h"

namespace beamid::solver {

struct MisfitLocationOptions {
  // Family-wise significance: the probability that a correct model has any
  // group flagged (Holm–Bonferroni over all groups tested).
  double family_significance = 0.01;
  // Parameters fitted to these residuals; subtracted from the overall test's
  // dof (the group tests ignore them, which makes them slightly conservative).
  int num_fitted_parameters = 0;
  // σ of the model's own error (discretisation, truncation, the beam's
  // damping law) as a fraction of the channel's model fundamental at the
  // step, added isotropically to every harmonic's covariance before
  // whitening: Cov = L·Lᵀ + (ε·|Y_c1|)²·I. A harmonic-balance model of the
  // paper's beam matches the time-domain simulator to ~1e-3 (harmonic 3 near
  // the second mode); 0 tests against the measurement noise alone, which
  // the diagnosis does under propagated σ: they hold every error stated
  // beforehand, and the demo's base fit reads reduced χ² 1.04 with them.
  double model_relative_error = 1e-3;
  // A group's excess χ² share must reach this to be named in a finding.
  double finding_min_share = 0.05;
  // Reconstruct the support's loops (needs the exact linear beam per step).
  bool analyse_loops = true;
  // Relative error of the loops beyond the phasor noise, added in quadrature
  // to σ(c_eq) and to σ of each part of M̃_k: the exact linear beam is not
  // the real one (its damping law, the sensors' attachment), which biases W
  // by ~1 % on simulated campaigns; real rigs are worse.
  double loop_relative_model_error = 0.03;

  // Throws beamid::InputError naming the first field out of its range, its
  // value and the range.
  void Validate() const;
};

// Which part of each residual pair a group tests, and which steps, by the
// names diagnosis.json gives them.
enum class ResidualPart { kBoth, kInPhase, kQuadrature };
inline constexpr schema::Name<ResidualPart> kResidualPartNames[] = {
    {ResidualPart::kBoth, "both"}, {ResidualPart::kInPhase, "in_phase"}, {ResidualPart::kQuadrature, "quadrature"}};
enum class FrequencyBand { kAll, kNearResonance, kAway };
inline constexpr schema::Name<FrequencyBand> kFrequencyBandNames[] = {
    {FrequencyBand::kAll, "all"}, {FrequencyBand::kNearResonance, "near_resonance"}, {FrequencyBand::kAway, "away"}};
inline std::string ToString(ResidualPart p) { return std::string(schema::NameOf(p, kResidualPartNames)); }
inline std::string ToString(FrequencyBand b) { return std::string(schema::NameOf(b, kFrequencyBandNames)); }

// One tested group of standardised residuals.
struct MisfitGroupTest {
  std::string channel;          // "" = all channels
  int harmonic = 0;             // 0 = all harmonics
  std::string level;            // "" = all levels
  ResidualPart part = ResidualPart::kBoth;
  FrequencyBand band = FrequencyBand::kAll;
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
  // The measured even harmonics (2, 4, …) of every channel against none:
  // significant at the family significance means the recordings carry them,
  // so that an even-harmonic misfit is the support's asymmetry and not the
  // model's spurious even-order terms.
  double measured_even_harmonics_p_value = 1.0;
  bool measured_even_harmonics = false;
  std::vector<double> harmonic_excess_chi2;  // [k−1], over all channels
  std::vector<double> channel_excess_chi2;   // [c] in data.channels order
  // Slope of log A_l vs log R_l over the levels l, where
  //   A_l = sqrt(Σ max(|e|²/σ_c² − 2σ²/σ_c², 0)/n_l)  the misfit beyond noise,
  //   R_l = sqrt(Σ |Y_c1|²/σ_c² / n_l)                the measured response,
  // e = Y_model − Y_measured, σ_c the channel's median σ (a level-independent
  // scale). 1: the misfit scales like the response (a linear error); > 1 it
  // grows faster (a nonlinearity the model lacks); ≈ 0 it does not grow.
  // Over the pairs of the significant channel×harmonic groups (all pairs
  // when none is). NaN with fewer than two levels showing misfit.
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
// Throws beamid::InputError on invalid options and std::invalid_argument
// when model and data disagree in size.
MisfitLocation LocateMisfit(const FitData& data, const std::vector<Eigen::MatrixXcd>& model, int fitted_harmonics,
                            const hb::LinearBeamModel& reference_beam, const MisfitLocationOptions& options = {});

}  // namespace beamid::solver
