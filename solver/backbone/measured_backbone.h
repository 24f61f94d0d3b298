// The measured nonlinear behaviour of one isolated mode, model-free, from
// stepped-sine first-harmonic points at several levels (force- or
// response-controlled): per level the phase-resonance point, the peak and the
// equivalent damping ratio by three methods; across levels the backbone
// (resonance frequency against response amplitude), damping against
// amplitude, and a single-nonlinear-mode fit ω_n(a), ζ(a)
// (solver/single_mode_fit.h: polynomials or Iwan-like power laws, A constant
// or A(a), chosen by AICc) that regenerates each level's curve.
//
// With the response converted to displacement X_d (signal/quantity_conversion.h),
// one nonlinear mode plus the other modes' nearly constant share R obeys
// X_d/F = A(a)/D(a, ω) + R, D = ω_n²(a) − ω² + 2iω ζ(a) ω_n(a), a = |X_d − R·F|,
// A complex (non-proportional damping) and changing with amplitude (the
// mode's shape at sensor and force changes as the nonlinearity stiffens). R
// is estimated once from all levels' points (when it lowers the AICc); left
// out, it bends the tails of every curve and biases A(a). Then:
//  - quadrature point (phase resonance, X_d 90° from F): at the step nearest
//    quadrature of the two that bracket it, the model's move to quadrature
//    at that step's own amplitude a_k: Re(A/D) + R = 0 with ω_n² = ω² +
//    Re(A·G'), ζω_n = Im(A·G')/(2ω), G' = F/(X_d − R·F); A(a_k) from the
//    global fit (which sees the amplitudes where A is pinned down by points
//    on both sides of a resonance). (Interpolating Re G in ω² between the
//    steps is biased when the amplitude changes much between them, and fails
//    across a jump; a constant real A taken from the lowest level is 9 % off
//    at the top of a hardening fold — +7.6 mHz, 3σ, at 9 N on the paper's
//    beam.) Its frequency uncertainty adds, to the propagated noise, A(a_k)'s
//    covariance from the global fit (the extrapolation, where the step lies
//    beyond the amplitudes seen on both sides) and the level's RMS departure
//    from one nonlinear mode (SingleModeFit's backbone residual);
//  - local single-mode fit: the model above with ω_n² quadratic and ζω_n
//    linear in a, A constant (complex), on the level's points whose |X_d/F|
//    is at least `fit_window` of its peak; its ω_n is the modal natural
//    frequency, which differs from the sensor's phase resonance by
//    (Im A/Re A)·ζω_n (a few mHz for a complex mode);
//  - half-power: from r = (ω₂² − ω₁²)/(4ω_p²), with |X_d/F| = peak/√2 at
//    ω₁, ω₂, ζ² = (1 − 1/√(1 + 4r²))/2; the peak ω_p² is the vertex of
//    1/|X_d/F|², a quadratic in ω², fitted to the steps above 1/√2 of the
//    largest, and each crossing is solved on the quadratic through the three
//    steps around it (exact for one linear mode, any spacing; biased when
//    the amplitude changes along a force-controlled curve, the other two
//    are not: flagged nonlinear_curve where the fit predicts that bias beyond
//    the σ). Not made across a jump, or without a crossing on both sides.
// The level's reported ζ (LevelResonance::damping_ratio) carries a σ that
// covers all three. Jumps of the sweep (solver/backbone/sweep_jumps.h) and a
// phase running against the convention (solver/backbone/phase_convention.h)
// are flagged.
// Uncertainties are the phasors' (and the frequency's) standard
// uncertainties propagated to first order (central-difference Jacobians).
// The fits' covariances hold R's uncertainty (estimated from the same
// points, it moves every parameter) and the amplitude's noise (a regressor
// the fits read from the same X_d as G): left out, a spurious R moved a
// linear level's natural frequency by 6 σ, and a Duffing level's by 25 σ.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "hb/enum_names.h"
#include "signal/first_harmonic_level.h"
#include "solver/backbone/single_mode_fit.h"
#include "solver/backbone/sweep_jumps.h"

namespace beamid::solver {

struct MeasuredBackboneOptions {
  // Points whose |X_d/F| reaches this fraction of the level's peak enter the
  // local and global fits (near the mode, where one mode dominates).
  double fit_window = 0.3;
  // A level whose force amplitude spreads (max/min − 1) by less than this is
  // force-controlled; else one whose response amplitude does is response-controlled.
  double constant_tolerance = 0.05;
  // Jumps between consecutive steps of the campaign (solver/backbone/sweep_jumps.h):
  // flagged ("jump"); no phase resonance or half-power point is taken across one.
  SweepJumpOptions jumps;
  // Model choice for the global fit: polynomial degrees 0..max of ω_n²(a) and ζω_n(a).
  int max_frequency_degree = 3;
  int max_damping_degree = 2;
  // Also the Iwan-like power laws p0 + p1·s^α, q0 + q1·s^β (exponents on a grid).
  bool try_power_laws = true;
  // Also A(a) = A0 + A2·s² (the mode's shape at sensor and force changing with amplitude).
  bool try_amplitude_dependent_modal_constant = true;
  // Take the other modes' share R (X_d/F = A/D + R) off before every fit.
  bool estimate_residual = true;
  // |slope|/σ above which the damping trend counts as significant.
  double trend_significance = 3.0;
  // A level's regeneration by the cross-level fit counts as beyond its noise
  // (flag regeneration_beyond_noise) when its relative RMS error exceeds both
  // kRegenerationNoiseFactor × what the phasors' noise alone explains and
  // this floor: one nonlinear mode is an approximation (residual modes, a
  // shape changing with amplitude) that misses clean data by a few per cent,
  // so a level is only flagged when it misses by more than 10 %.
  double max_regeneration_relative_rms = 0.10;
  // Flagged levels (LevelResonance::flags) stay out of the cross-level fit and
  // the damping trend unless this asks to keep them.
  bool keep_flagged_levels_in_fit = false;

  // Throws InputError naming the field, its value and the allowed range.
  void Validate() const;
};

struct Estimate {
  double value = 0.0;
  double std = 0.0;
  bool valid = false;
};

enum class LevelControl { kForce, kResponse, kNeither };

// What makes a level's numbers untrustworthy. Names (LevelFlagName):
// "damping_not_positive" (an estimator's ζ ≤ 0), "peak_outside_band" (the
// peak, phase resonance or natural frequency outside the level's measured
// frequencies, or the largest response at the sweep's end),
// "regeneration_beyond_noise" (the cross-level single-mode fit misses the
// level by more than its noise allows, see
// MeasuredBackboneOptions::max_regeneration_relative_rms), "jump" (the
// response jumped between two consecutive steps of the sweep, up or down:
// the curve is folded, its peak is the fold's edge and one side of it lies
// on another branch; LevelResonance::jumps says where), "phase_convention"
// (the phase runs through the resonance the other way than beamid's
// convention gives, or half a turn from a drive point's: another sign
// convention, a sensor mounted upside down; solver/backbone/phase_convention.h),
// "coarse_steps" (fewer than kMinStepsInHalfPowerBand steps between the
// half-power frequencies: exact for one linear mode, but any departure from
// it — noise, nonlinearity, a second mode — is read between steps that do
// not see the peak; the half-power ζ then does not enter the level's ζ),
// "off_backbone" (the cross-level fit misses the level beyond its noise while
// the level's own single-mode curve holds it: the levels do not lie on one
// backbone — drift over the test's history, the beam warming, a contact
// bedding in — and no level is worse than the others for it, so it stays in
// the fit; a level its own curve misses too is regeneration_beyond_noise),
// "nonlinear_curve" (the peak frequency, half-power ζ or half-power natural
// frequency, which read the curve as one linear mode's, are biased on it by
// more than their σ — the amplitude changing along a force-controlled curve,
// another mode's share skewing it — as the same estimator read on the
// noise-free curve of the fit that holds the level (the cross-level fit, or
// off a drifting backbone the level's own) predicts, beyond twice that
// prediction's own uncertainty; such a half-power ζ stays out
// of the level's ζ, and like coarse_steps the flag concerns one estimator,
// not the level's points).
enum class LevelFlagKind {
  kDampingNotPositive,
  kPeakOutsideBand,
  kRegenerationBeyondNoise,
  kJump,
  kPhaseConvention,
  kCoarseSteps,
  kOffBackbone,
  kNonlinearCurve
};

// Steps between the half-power frequencies below which the half-power ζ is flagged.
inline constexpr int kMinStepsInHalfPowerBand = 5;

// Regeneration errors up to this many times what the noise alone explains are not flagged.
inline constexpr double kRegenerationNoiseFactor = 3.0;

struct LevelFlag {
  LevelFlagKind kind = LevelFlagKind::kDampingNotPositive;
  // The LevelResonance number it concerns: "quadrature_damping_ratio",
  // "local_damping_ratio", "half_power_damping_ratio",
  // "free_decay_damping_ratio", "quadrature_frequency",
  // "peak_frequency", "half_power_natural_frequency",
  // "local_natural_frequency", "regeneration_relative_rms", "sweep" (a jump)
  // or "phase" (the phase convention).
  std::string quantity;
  std::string message;  // with the numbers
};

// One point of a level's frequency response as the report draws it: |X_d/F|
// and the phase of X_d against F (beamid's convention: −π/2 at a phase
// resonance); NaN where not known.
struct LevelFrfPoint {
  double frequency_hz = 0.0;
  double receptance_m_N = 0.0;
  double phase_rad = 0.0;
};

struct LevelResonance {
  std::string label;
  LevelControl control = LevelControl::kForce;
  int num_points = 0;
  int num_fit_points = 0;

  // Phase resonance.
  Estimate quadrature_frequency_hz;
  Estimate quadrature_amplitude_m;         // |X_d| there
  Estimate quadrature_response_amplitude;  // in the level's response quantity, SI
  Estimate quadrature_force_N;
  Estimate quadrature_damping_ratio;
  // The level's sweep jumped (see `jumps`): no phase resonance is taken
  // across a jump (a down-sweep's jump onto the upper branch crosses
  // quadrature without passing through resonance), no half-power points.
  bool quadrature_after_jump = false;
  std::string quadrature_note;
  // In the campaign's (run) order of the steps.
  std::vector<SweepJump> jumps;

  // Peak of |X_d/F|: vertex of 1/|X_d/F|², a quadratic in ω² for one mode, through the three highest steps.
  // Not taken on a sweep that jumped (its largest step is the fold's edge). Flagged nonlinear_curve, as the
  // half-power ζ and f_n, where the cross-level fit predicts the method's bias on the level beyond its σ.
  Estimate peak_frequency_hz;
  Estimate peak_receptance_m_N;
  Estimate peak_amplitude_m;

  // Half-power: ζ, the two frequencies where |X_d/F| = peak/√2 and the
  // natural frequency ω_p/√(1 − 2ζ²) (all invalid, with the reason in the
  // note, unless the curve crosses 1/√2 of its peak on both sides of it
  // without a jump).
  Estimate half_power_damping_ratio;
  Estimate half_power_lower_frequency_hz;
  Estimate half_power_upper_frequency_hz;
  Estimate half_power_natural_frequency_hz;
  std::string half_power_note;

  // Local single-mode fit, evaluated at the quadrature amplitude (ω_n: the modal natural frequency).
  Estimate local_natural_frequency_hz;
  Estimate local_damping_ratio;
  double local_reduced_chi_square = 0.0;

  // After steps whose excitation stops before the record ends: the ring-down
  // of the step nearest the phase resonance (else the peak), window by
  // window in falling amplitude (signal/free_decay.h), and its first window's
  // ζ, at the amplitude nearest the steady one. Independent of the
  // steady-state estimators and not combined with them: a ring-down passes
  // through every amplitude below the level's.
  std::vector<signal::DecayPoint> free_decay;
  double free_decay_step_frequency_hz = 0.0;
  Estimate free_decay_damping_ratio;

  // The level's damping ratio as reported: the phase-resonance estimate (else
  // the local fit's, else the half-power one), its σ widened to cover the
  // other estimators (|ζ_k − ζ| ≤ σ for each valid ζ_k): where the mode's
  // shape or the amplitude changes along the curve they measure different
  // things, and the propagated noise alone would claim a precision none has.
  // The note names the estimators and which to trust when they part by more
  // than their own noise ("" when they agree).
  Estimate damping_ratio;
  std::string damping_ratio_note;

  // The global fit regenerating this level's fitted points: the response
  // from the measured force (force-controlled or neither) or the force from
  // the measured response (response-controlled).
  double regeneration_relative_rms = 0.0;
  double regeneration_max_relative = 0.0;
  double regeneration_reduced_chi_square = 0.0;
  // The relative RMS error the phasors' noise alone would give (0: no noise given).
  double regeneration_noise_relative_rms = 0.0;
  // The level's own single-mode curve (its local fit) regenerating the same
  // points: within the noise while the cross-level fit is not, the level is
  // sound and the levels disagree with each other (flag off_backbone).
  // 0 without a local fit.
  double own_curve_relative_rms = 0.0;
  // When the table states no uncertainty: the response's relative noise
  // estimated from the sweep's own scatter about a smooth curve, and used as
  // its σ for every number, flag and jump of the level (0 when stated).
  double noise_from_sweep_relative_rms = 0.0;

  // The level's steps in the campaign's (run) order, the ones `jumps`
  // counts; and the cross-level fit regenerating the level at and between
  // its steps (as `regeneration_*` does at the fitted ones), in frequency
  // order, empty without that fit: a person sees where the fit departs.
  std::vector<LevelFrfPoint> measured_frf;
  std::vector<LevelFrfPoint> fit_frf;

  // Empty for a level whose numbers pass the checks.
  std::vector<LevelFlag> flags;
  // Whether the level's points entered the cross-level fit and damping trend.
  bool in_global_fit = true;

  bool HasFlag(LevelFlagKind kind) const;
  // The flags on one quantity, each kind once with its count, e.g. "[FLAG: not
  // positive]", "[FLAG: jump ×3]"; "" when none.
  std::string FlagNote(std::string_view quantity) const;
};

struct BackboneModelCandidate {
  int frequency_degree = 0;
  int damping_degree = 0;
  double aicc = 0.0;
  double reduced_chi_square = 0.0;
  double frequency_exponent = 0.0;  // > 0: power law (Iwan-like), exponent chosen
  double damping_exponent = 0.0;
  bool amplitude_dependent_modal_constant = false;
  std::string form;  // SingleModeFit::FormName()
};

// How damping changes with amplitude, from the global fit with ζω_n linear
// in a. Judged on ζω_n (the damping rate, c/2m of one mode), not on ζ: a
// constant viscous damper keeps ζω_n constant, so its ζ = ζω_n/ω_n rises
// wherever the frequency falls (a softening support) and falls where it
// rises; only a rate that changes with amplitude is damping that does.
enum class Trend { kNotJudged, kRises, kFalls, kNone };
// The verdict on ζω_n, as files and reports word it; files written before
// the damping rate judged ζ alone with the words of the second table.
inline constexpr schema::Name<Trend> kDampingRateTrendNames[] = {
    {Trend::kRises, "rises beyond a constant damper"}, {Trend::kFalls, "falls below a constant damper"},
    {Trend::kNone, "consistent with a constant damper"}, {Trend::kNotJudged, ""}};
// The verdict on ζ alone.
inline constexpr schema::Name<Trend> kDampingRatioTrendNames[] = {
    {Trend::kRises, "rises"}, {Trend::kFalls, "falls"}, {Trend::kNone, "no significant trend"}, {Trend::kNotJudged, ""}};

struct DampingTrend {
  double amplitude_m = 0.0;
  // dζ/da at `amplitude_m`, its σ and z = slope/σ.
  double slope_per_m = 0.0;
  double slope_std_per_m = 0.0;
  double z = 0.0;
  // d(ζω_n)/da [1/(s·m)], its σ and z.
  double damping_rate_slope_per_s_m = 0.0;
  double damping_rate_slope_std_per_s_m = 0.0;
  double damping_rate_z = 0.0;
  // On ζω_n (kDampingRateTrendNames) and on ζ alone (kDampingRatioTrendNames);
  // kNotJudged when the cross-level fit failed.
  Trend verdict = Trend::kNotJudged;
  Trend damping_ratio_verdict = Trend::kNotJudged;
  // Why the verdicts are not judged, "" when they are.
  std::string note;
};

// A damping trend is judged only where at least this many levels passed
// their checks (no flag but coarse_steps or off_backbone) and the others left the fit.
inline constexpr int kMinCleanLevelsForTrend = 2;

struct MeasuredBackbone {
  std::string response_quantity;  // of the input levels
  // What drives them (signal/quantity.h names): "force", "voltage" or
  // "base_acceleration"; receptances and force amplitudes are per its unit.
  std::string excitation_quantity = "force";
  std::vector<LevelResonance> levels;
  SingleModeFit fit;  // the chosen global single-nonlinear-mode fit (FormName() says which)
  std::vector<BackboneModelCandidate> candidates;
  double min_amplitude_m = 0.0, max_amplitude_m = 0.0;  // of the fitted points
  DampingTrend damping_trend;
  std::vector<std::string> warnings;
};

// Throws std::invalid_argument when the levels mix response quantities or a
// level has fewer than 3 points.
MeasuredBackbone AnalyseMeasuredBackbone(const std::vector<signal::FirstHarmonicLevel>& levels,
                                         const MeasuredBackboneOptions& options = {});

std::string_view LevelControlName(LevelControl control);
// What controls a level in the words of its excitation: "force", "voltage",
// "base acceleration" (LabelsOf(excitation_quantity).control), else
// "response" or "neither".
std::string LevelControlText(std::string_view excitation_quantity, LevelControl control);

// The words that label a backbone's numbers honestly for its excitation:
// what controls a level ("force", "voltage", "base acceleration"), the
// excitation's SI unit, the CSV column of its amplitude and what X/F is.
struct ExcitationLabels {
  std::string control;  // "force", "voltage", "base acceleration"
  std::string unit;     // "N", "V", "m/s^2"
  std::string column;   // "force_N", "voltage_V", "minus_base_acceleration_m_s2"
  std::string frf;      // "receptance [m/N]", "displacement per drive voltage [m/V]", ...
  std::string caveat;   // what it means for f_n and ζ ("" for a force)
};
// Throws InputError for a name that is no excitation quantity.
ExcitationLabels LabelsOf(std::string_view excitation_quantity);
std::string_view LevelFlagName(LevelFlagKind kind);
// Throws InputError for a name LevelFlagName does not give.
LevelFlagKind LevelFlagKindFromName(std::string_view name);

}  // namespace beamid::solver
