// What a fit sees of a campaign: per step the excitation frequency, the
// measured force phasors (all harmonics: they drive the model) and, for each
// fitted channel, the measured response phasors of harmonics 1..K with the
// whitening matrices of their uncertainties. Built from signal/'s PhasorSet.
//
// Weighted residual of channel c, harmonic k, step i (2 reals):
//     r = L⁻¹ (Y_model − Y_measured),   L Lᵀ = Cov(Re Y, Im Y)
// so that Σ|r|² is χ² when the uncertainties are right.
#pragma once

#include <complex>
#include <numbers>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "hb/beam_properties.h"
#include "hb/enum_names.h"
#include "hb/linear_attachments.h"
#include "solver/estimation/phasor_uncertainty.h"
#include "signal/campaign.h"
#include "signal/phasor_set.h"

namespace beamid::solver {

// How a response phasor's σ is made (FitDataOptions::uncertainty).
enum class PhasorUncertainty { kRelativeFloor, kPropagated };
// result.json's names, and the command line's (--phasor-uncertainty).
inline constexpr schema::Name<PhasorUncertainty> kPhasorUncertaintyNames[] = {
    {PhasorUncertainty::kRelativeFloor, "relative_floor"}, {PhasorUncertainty::kPropagated, "propagated"}};

struct FitChannel {
  std::string channel;
  double position_m = 0.0;
  int derivative_order = 2;  // 0 displacement, 1 velocity, 2 acceleration
};

// (ikω)^d: turns harmonic k's displacement phasor into the phasor of a
// channel that measures the d-th time derivative (e^{+iωt} convention).
inline std::complex<double> DerivativeFactor(int derivative_order, double k_omega_rad_s) {
  std::complex<double> factor(1.0);
  for (int d = 0; d < derivative_order; ++d) factor *= std::complex<double>(0.0, k_omega_rad_s);
  return factor;
}

struct FitStep {
  std::string level;
  std::string file;
  double omega_rad_s = 0.0;
  // The frequency campaign.json states for the step (the generator's
  // setting, on its own clock); 0 when unknown. Beside the frequency read
  // from the record it shows the acquisition's clock error.
  double nominal_frequency_hz = 0.0;
  Eigen::VectorXcd force_N;              // F_0..F_H of the recording (F_0 = 0: transducers are AC)
  Eigen::MatrixXcd measured;             // channels × harmonics 1..K, SI of each channel's quantity
  std::vector<std::vector<Eigen::Matrix2d>> whitening;  // [channel][k-1]: L⁻¹
  Eigen::MatrixXd std_amplitude;         // channels × K: σ of the real/imag parts (rms of the two)
  // [channel][k-1]: what std_amplitude is made of (phasor_uncertainty.h),
  // as the data were read (a corrected recording fault leaves it as it was).
  std::vector<std::vector<PhasorUncertaintyBudget>> uncertainty_budget;
  // [source]: channels × K, the change of each measured phasor (or of the
  // model's, which is driven with them) for a one-σ error of what the whole
  // step shares: the force's amplitude, its phase (every response is
  // referred to it) and the frequency. Each phasor's own share is in its
  // covariance already; the correlation across the step's channels and
  // harmonics enters the parameters' covariance (shared_step_errors.h).
  // Empty under the relative floor.
  std::vector<Eigen::MatrixXcd> shared_errors;
  // The extraction found the record cut before it settled and raised its
  // phasors' uncertainty by what is left of the transient (the change
  // between the analysed part's halves, |ΔX_1|/|X_1| of the worst channel;
  // signal/settling_uncertainty.h). 0: settled.
  double unsettled_change_relative = 0.0;
  bool unsettled = false;

  double FrequencyHz() const { return omega_rad_s / (2.0 * std::numbers::pi); }
};

struct FitData {
  hb::BeamProperties beam;               // nominal, from campaign.json
  double force_position_m = 0.0;
  hb::LinearAttachments sensor_masses;   // the masses campaign.json gives
  std::vector<FitChannel> channels;
  int num_fit_harmonics = 3;             // K
  std::vector<FitStep> steps;
  std::vector<std::string> levels;       // distinct labels in campaign order
  PhasorUncertainty uncertainty = PhasorUncertainty::kRelativeFloor;  // how the σ were made

  int NumResiduals() const { return static_cast<int>(2 * channels.size() * num_fit_harmonics * steps.size()); }
  double MeanOmega_rad_s() const;  // the steps' mean angular frequency (1 without steps)
};

struct FitDataOptions {
  std::vector<std::string> channels;     // response channels to fit (empty: all)
  int num_fit_harmonics = 3;             // K: harmonics 1..K are fitted
  // How a response phasor's σ is made (phasor_uncertainty.h gives both
  // budgets):
  // - kRelativeFloor: the record's noise, raised to relative_uncertainty_floor
  //   × the channel's largest fundamental over the campaign. It stands in
  //   for the force's and frequency's errors and the model's own at once,
  //   and weighs a step far from resonance, and every harmonic above the
  //   first, well below its noise: the demo's fit reads a reduced χ² of 0.02.
  // - kPropagated: the record's noise plus the force's and the frequency's
  //   errors propagated into each phasor, plus a stated model error ε
  //   (relative_model_error) relative to the phasor itself. On the paper's
  //   campaign the reduced χ² is 1.04. What the fit leaves beyond these σ
  //   is estimated per harmonic as the residual model error
  //   (model_error.h), reported and propagated on its own.
  PhasorUncertainty uncertainty = PhasorUncertainty::kRelativeFloor;
  double relative_uncertainty_floor = 1e-4;
  // ε stated beforehand (kPropagated only), beside the one the fit
  // estimates: 0, since the harmonic balance agrees with independent
  // solutions at 1e-7 and below and the rest is for the data to show, not
  // for a fixed number to stand in for.
  double relative_model_error = 0.0;
  // Force harmonics k ≥ 2 that do not stand out of the transducer's noise
  // are not force on the beam: the model is driven with 0 there. Driving it
  // with the noise puts spurious harmonics into every predicted response,
  // and near a higher mode (3ω at the second) one such harmonic alone
  // misfits its step by χ² ~ 1700. The test is |L⁻¹F_k|² (χ², 2 dof) above
  // −2·ln(α/n), n the campaign's force harmonics tested: Bonferroni over the
  // campaign, so that noise drives the model at any step of a campaign with
  // probability α. Per harmonic at p = 0.001 it did in 10 % of the paper's
  // 27-step campaigns.
  double force_harmonic_family_significance = 1e-3;

  // |L⁻¹F_k|² a force harmonic of this data must reach to drive the model.
  double ForceHarmonicChiSquareThreshold(int num_tested) const;

  // Throws InputError naming the field, its value and the allowed range.
  void Validate() const;
};

// Throws std::invalid_argument naming an unknown channel or a missing harmonic.
FitData MakeFitData(const signal::Campaign& campaign, const signal::PhasorSet& phasors,
                    const FitDataOptions& options);

}  // namespace beamid::solver
