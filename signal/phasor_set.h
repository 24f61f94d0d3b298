// The product of signal/: per step of a campaign, the estimated excitation
// frequency and, for every channel, the complex peak phasors X_k of harmonics
// 1..H in SI units (docs/fourier-convention.md: x(t) = X_0 + Σ Re(X_k e^{ikωt})),
// phase-referenced to the force: every step's phasors are rotated so that the
// force fundamental F_1 is real and positive, harmonic k by k times that angle.
//
// Uncertainty: each phasor carries the standard uncertainties of its real and
// imaginary parts and their correlation — the 2×2 covariance
//     [σ_re², ρσ_reσ_im; ρσ_reσ_im, σ_im²]
// of (Re X_k, Im X_k) — from the measured noise floor near harmonic k,
// including the uncertainty of the force phase used as reference (so the
// force fundamental has σ_im = 0). Amplitude and phase uncertainties follow by
// linearisation; they are meaningful when |X_k| ≫ σ.
#pragma once

#include <complex>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>

#include "signal/free_decay.h"
#include "signal/quantity.h"

namespace beamid::signal {

struct HarmonicPhasor {
  int harmonic = 1;                   // k
  std::complex<double> value;         // X_k, SI, peak
  double std_real = 0.0;              // standard uncertainty of Re X_k
  double std_imag = 0.0;              // standard uncertainty of Im X_k
  double correlation = 0.0;           // ρ between Re and Im errors

  double Amplitude() const { return std::abs(value); }
  double PhaseRad() const { return std::arg(value); }
  Eigen::Matrix2d Covariance() const;
  void SetCovariance(const Eigen::Matrix2d& covariance);
  double AmplitudeStd() const;  // σ of |X_k| (linearised)
  double PhaseStdRad() const;   // σ of arg X_k (linearised)
};

struct ChannelPhasors {
  std::string channel;
  Quantity quantity = Quantity::kForce;
  double position_m = 0.0;
  double mean = 0.0;                      // X_0 (SI)
  std::vector<HarmonicPhasor> harmonics;  // k = 1..H in order
  double thd = 0.0;                       // √(Σ_{k≥2}|X_k|²)/|X_1| over the fitted harmonics
  double snr_db = 0.0;                    // 10·log10(Σ|X_k|²/2 / residual variance)
  double noise_rms = 0.0;                 // residual RMS (SI)

  // Harmonic k (1-based); throws std::out_of_range.
  const HarmonicPhasor& Harmonic(int k) const;
};

struct StepQuality {
  double snr_db = 0.0;               // the worst channel's
  double settled_after_s = 0.0;      // transient dropped from the start of the record
  double analysed_duration_s = 0.0;  // steady part used for the phasors
  std::string settling;              // why that much was dropped (or "no transient detected")
  std::vector<std::string> warnings;  // the result stands; the engineer should look
  std::vector<std::string> notes;     // recorded, nothing to do
  // A record cut before it settled (signal/settling_uncertainty.h): its
  // phasors' uncertainty includes the change between the analysed part's
  // halves, |ΔX_1|/|X_1| of the worst channel. 0: not raised.
  bool unsettled = false;
  double unsettled_change_relative = 0.0;
  std::string unsettled_channel;
  // Ringing of the last frequency step, fitted out of the phasors
  // (signal/settling_transient.h): its amplitude at the analysed part's start
  // over |X_1| in the channel where that is largest, its decay rate and its
  // beat against the drive.
  bool ringing = false;
  double ringing_relative = 0.0;
  double ringing_decay_rate_per_s = 0.0;
  double ringing_beat_hz = 0.0;
  std::string ringing_channel;
};

struct StepPhasors {
  std::string file;                 // as in campaign.json
  std::string level;
  double nominal_frequency_hz = 0.0;
  double frequency_hz = 0.0;        // estimated from the force
  double frequency_std_hz = 0.0;
  ChannelPhasors force;             // F_1 real positive
  std::vector<ChannelPhasors> responses;  // campaign sensor order
  StepQuality quality;
  // After an excitation that stops before the record ends: each analysed
  // response's ring-down (signal/free_decay.h), empty otherwise.
  std::vector<FreeDecay> free_decays;

  double Omega_rad_s() const;
  // The force or a response by channel name; nullptr if absent.
  const ChannelPhasors* Find(std::string_view channel) const;
};

// A step the extraction left out (ExtractOptions::skip_bad_steps), and why.
struct SkippedStep {
  std::string file;
  std::string level;
  double nominal_frequency_hz = 0.0;
  std::string reason;  // the errors found in its recording
};

struct PhasorSet {
  std::string campaign;        // campaign name
  std::string campaign_sha256;  // the campaign's content hash (signal/campaign_hash.h); "" in older files
  int num_harmonics = 0;       // H requested
  std::vector<StepPhasors> steps;  // campaign order
  std::vector<SkippedStep> skipped;  // campaign order
};

}  // namespace beamid::signal
