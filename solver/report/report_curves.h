// The numbers behind the plots of `beamid report`, from an identified model
// (result.json), its campaign and the campaign's phasors:
//  - per level and channel, the measured first harmonic X_1 (amplitude, and
//    its phase against the force) and the model's frequency response curve
//    (hb/continuation) under a pure sine of the level's mean measured force
//    amplitude |F_1|, with its stability; the amplitudes of harmonics 2 and 3
//    of both where the phasors and the model hold them;
//  - the model's backbone at the reference channel (the first fitted one) as
//    it is measured there (solver/estimation/sensor_backbone.h: the channel's first
//    harmonic in quadrature with the force), and the measured phase-resonance
//    point of every level with its uncertainty, from the model-free analysis
//    of `beamid backbone --measured` (solver/measured_backbone.h), which also
//    handles a level whose sweep jumps (folds) before quadrature;
//  - at the first held-out channel, predicted (solver/prediction.h, with its
//    standard uncertainty) and measured steady-state acceleration over one
//    period, at each level's step of largest response; "measured" is the
//    recording's harmonics 1..H (signal/), phase-referenced to the force like
//    the model;
//  - the residual map: per fitted channel c, harmonic k and step i the norm of
//    the whitened misfit |L⁻¹(Y_model − Y_measured)| (solver/fit_data.h), whose
//    squares sum to the fit's χ².
// Amplitudes are in SI of each channel's quantity.
#pragma once

#include <cmath>
#include <complex>
#include <functional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "signal/campaign.h"
#include "signal/phasor_set.h"
#include "solver/backbone/measured_backbone.h"
#include "solver/estimation/prediction.h"
#include "solver/estimation/result_file.h"

namespace beamid::solver {

struct ReportChannel {
  std::string channel;
  double position_m = 0.0;
  int derivative_order = 2;  // 0 displacement, 1 velocity, 2 acceleration
  std::string si_unit;
  bool fitted = false;
};

// The highest harmonic whose amplitude the response plots show.
constexpr int kReportHarmonics = 3;

// The phase of a response phasor X (of a quantity of the given derivative
// order: 0 displacement, 1 velocity, 2 acceleration) per unit force F, as the
// phase of the displacement against the force, in degrees, in (−180, 180]:
// arg(X/F) − order·90°. One convention for every sensor, so that a phase
// resonance reads −90° (+90° where the mode's shape has the other sign).
double DisplacementPhaseDeg(std::complex<double> response_per_force, int derivative_order);

struct ModelCurvePoint {
  double frequency_hz = 0.0;
  std::vector<double> amplitude;  // per channel: |X_1|
  bool stable = true;
  std::vector<double> phase_deg;  // per channel: DisplacementPhaseDeg(X_1/F_1); empty: not known
  // per channel, |X_k| for k = 2..kReportHarmonics (NaN where the model has
  // fewer harmonics); empty: not known
  std::vector<std::vector<double>> higher_harmonics;
};

struct MeasuredPoint {
  double frequency_hz = 0.0;
  std::vector<double> amplitude;  // per channel: |X_1|
  std::string file;
  // Why the step is not to be trusted as the others ("" when it is): the
  // extraction found its record cut before it settled, the robust fit left
  // it out as an outlier (result.json robust_fit), or both.
  std::string flag;
  double force_amplitude_N = NAN;                     // this step's |F_1|; NaN: the level's mean stands for it
  std::vector<double> phase_deg;                      // as ModelCurvePoint
  std::vector<std::vector<double>> higher_harmonics;  // as ModelCurvePoint (NaN where not extracted)
};

struct LevelCurves {
  std::string level;
  double force_amplitude_N = 0.0;
  std::vector<MeasuredPoint> measured;  // steps of the level, campaign order
  std::vector<ModelCurvePoint> model;   // continuation order
  bool model_complete = true;
  std::string model_message;
};

struct AmplitudePoint {
  double frequency_hz = 0.0;
  double amplitude = 0.0;
  std::string level;
};

// A level's measured phase resonance beside the model's backbone.
struct MeasuredResonance {
  std::string level;
  double frequency_hz = 0.0, frequency_std_hz = 0.0;
  double amplitude = 0.0, amplitude_std = 0.0;  // in the reference channel's quantity, SI
  double damping_ratio = 0.0, damping_ratio_std = 0.0;  // from the quadrature point
  // The model's backbone frequency at this amplitude (NaN outside its range)
  // and the difference in standard uncertainties of the measured point.
  double model_frequency_hz = 0.0;
  double z = 0.0;
  std::string note;  // e.g. a jump before quadrature
};

// The model-free view across levels at the reference channel: per level the
// damping ratio by the three estimators of solver/measured_backbone.h, and
// the single-nonlinear-mode fit ω_n(a), ζ(a) with its ±2σ band.
struct MeasuredDampingPoint {
  std::string level;
  double amplitude = 0.0;  // at the phase resonance, in the reference channel's quantity, SI
  double quadrature = NAN, quadrature_std = NAN;
  double local = NAN, local_std = NAN;
  double half_power = NAN, half_power_std = NAN;
};

struct SingleModeCurvePoint {
  double amplitude = 0.0;  // in the reference channel's quantity, SI
  double frequency_hz = 0.0, frequency_std_hz = 0.0;
  double damping_ratio = 0.0, damping_ratio_std = 0.0;
};

struct MeasuredNonlinearMode {
  std::vector<MeasuredDampingPoint> damping;
  std::vector<SingleModeCurvePoint> fit;  // empty when the fit failed
  std::string fit_form;                   // SingleModeFit::FormName()
  Trend damping_rate_trend = Trend::kNotJudged;  // ζω_n against a constant damper
  double damping_rate_trend_z = 0.0;
};

struct TimeHistory {
  std::string level;
  double frequency_hz = 0.0;
  std::vector<double> time_s, predicted, predicted_std, measured;  // acceleration [m/s²]
};

struct ResidualMap {
  std::vector<std::string> rows;        // "acc1 h1", …: channel-major
  std::vector<std::string> step_level;  // per column
  std::vector<double> step_frequency_hz;
  Eigen::MatrixXd whitened_norm;        // rows × steps
};

struct ReportCurves {
  std::vector<ReportChannel> channels;
  std::vector<LevelCurves> levels;
  int reference_channel = 0;                  // index in channels
  std::vector<AmplitudePoint> backbone;       // model, at the reference channel
  std::vector<MeasuredResonance> phase_resonance;  // measured, at the reference channel
  std::vector<std::string> phase_resonance_warnings;
  MeasuredNonlinearMode measured_mode;  // at the reference channel
  std::string held_out_channel;               // empty: none
  std::vector<TimeHistory> time_histories;
  ResidualMap residuals;
};

struct ReportCurveOptions {
  int frc_max_points = 600;    // per level
  int backbone_points = 60;
  int samples_per_period = 96;  // time histories
};

// A level's measured points (no model curve): |X_1|, phase and harmonics of
// every channel at each of its steps, campaign order.
LevelCurves MeasuredLevelCurves(const signal::PhasorSet& phasors, const std::vector<ReportChannel>& channels,
                                const std::string& level);

// `progress(fraction, what)` is called as the work advances.
ReportCurves ComputeReportCurves(const ResultFile& result, const signal::Campaign& campaign,
                                 const signal::PhasorSet& phasors, const ReportCurveOptions& options = {},
                                 const std::function<void(double, const std::string&)>& progress = {});

}  // namespace beamid::solver
