// The next step of a running test, chosen for what it teaches. Each level is
// swept one way through the band, as a stepped-sine test runs: upwards, or
// downwards when the fitted model's response at that level peaks below the
// linear resonance by more than its half-power half-width (a softening
// support), so that a jump is approached from the side the resonant branch
// is followed from. The way is chosen when the level begins, from a fit
// within the noise (else upwards), and kept. The candidates are every
// frequency ahead of each level's last step on a grid of resolution_hz, at
// most max_step_hz ahead (beyond, the beam may land on another branch of a
// fold); a level not begun may start anywhere between its end of the band
// and the linear resonance, where the branch is single. For each candidate c
// the fitted model gives
// the sensitivities J_c = ∂Y/∂p of the responses it would measure, each
// whitened by the σ that record length would give (the noise seen so far,
// a floor and a part proportional to the response, both ∝ 1/√T); the gain
// is D_s-optimal on the target parameters T:
//     gain_c = log det Cov_T − log det [(Cov⁻¹ + J_cᵀJ_c)⁻¹]_T,
// and the step chosen, with its record length, is the one of largest gain
// per second of rig time (settle + record). Near resonance and near a fold the sensitivities are
// largest, so the steps grow dense there and stay sparse on the flanks.
//
// Settle time: after a change of frequency or level the response's
// transient decays as e^(−σ_d·t), σ_d = ζ₁ω₁ the first mode's decay rate
// (the fitted linear model's half-power half-width), from an amplitude of
// the change of the steady state, |ΔY| = |Y(candidate) − Y(last step)|
// (the model's prediction against the last step's measurement, the largest
// relative change over the channels). It has settled to settle_tolerance
// of |Y| after
//     t_settle = ln(max(e, |ΔY|/(settle_tolerance·|Y|)))/σ_d,
// so a small step next to the last one settles sooner than a jump across
// the band or to another level, and the gain per second says which is
// worth it.
#pragma once

#include <cmath>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "solver/estimation/fit_data.h"
#include "solver/estimation/model_family.h"
#include "solver/estimation/model_options.h"
#include "solver/estimation/model_structure.h"
#include "solver/live/test_plan.h"

namespace beamid::solver {

struct PlannerOptions {
  std::vector<PlanLevel> levels;  // the force levels the test may use
  double band_low_hz = 0.0;       // the band each level is swept through
  double band_high_hz = 0.0;
  double resolution_hz = 0.05;    // the candidates' frequency grid
  double max_step_hz = 1.0;       // the largest step ahead on a level
  // The parameters whose precision the test is for, and the σ each must
  // reach (absolute, in its unit); a target without a σ must reach
  // target_relative_std of its value.
  std::vector<std::string> targets = {"k1", "k3", "c"};
  std::map<std::string, double> target_std;
  double target_relative_std = 0.01;
  // Nothing measurable remains once the best step would lower log det of
  // the targets' covariance by less than this [nats].
  double min_gain = 0.01;
  int max_steps = 300;
  // Relative amplitude of the transient left when recording: at 1e-4 the
  // paper's campaigns near resonance missed by a reduced χ² of 3, at 1e-6
  // they fit within the noise.
  double settle_tolerance = 1e-6;
  double min_settle_s = 0.2;
  double max_settle_s = 30.0;
  double max_record_s = 10.0;  // records are chosen between the last step's need and this

  // Throws InputError naming the field, its value and the allowed range.
  void Validate() const;
};

// The fit the plan rests on: its data, model and parameters' covariance.
struct PlannerFit {
  const FitData* data = nullptr;
  const ModelFamily* family = nullptr;
  const ModelStructure* structure = nullptr;  // values = the fit's
  ModelOptions model;
  Eigen::MatrixXd covariance;  // physical parameters, structure order
  std::vector<double> analysed_s;  // per step of data: the steady record its σ come from
  // A fit that misses the data beyond their noise says little of where the
  // resonance leans: a level begun on it is swept upwards, as is usual.
  bool within_noise = true;
};

// The fitted linear model's first resonance (the law's k1 and c and the
// linear parameters applied): the peak of the driving point's response and
// its half-power half-width σ_d = ζ₁ω₁ [1/s], the decay rate of a
// transient; NaN when the peak is not found within ±10 % of ω₁.
struct LinearResonance {
  double frequency_hz = NAN;
  double decay_rate_per_s = NAN;
};
LinearResonance FirstResonance(const FitData& data, const ModelStructure& structure);

struct CandidateChoice {
  std::optional<PlannedStep> step;  // nullopt: nothing left worth measuring
  std::string why_none;
  int candidates = 0;
  // The targets' σ expected after the chosen step (structure order of targets).
  std::vector<double> expected_std;
};

// Where two competing causes differ most (a diagnosis's measurement
// suggestion): the candidates are then that level's frequencies in that
// band not yet measured, whatever the sweep's direction.
struct PlanFocus {
  std::string level;
  double low_hz = 0.0, high_hz = 0.0;
};

// A level begun: the frequency measured last (the highest of an upward
// sweep, the lowest of a downward one) and the way it goes.
struct LevelSweep {
  double last_hz = 0.0;
  SweepDirection direction = SweepDirection::kUp;
};

// The way to sweep a level not yet begun, and why (see above).
struct SweepChoice {
  SweepDirection direction = SweepDirection::kUp;
  double peak_hz = NAN;            // the fitted model's response peak at the level's force
  double linear_peak_hz = NAN;     // the fitted linear model's
  double half_width_hz = NAN;      // its half-power half-width
};
SweepChoice ChooseSweepDirection(const PlannerFit& fit, const PlanLevel& level, const PlannerOptions& options);

// `swept`: each level begun (a level absent is not begun). `last_step`: the
// step of fit.data measured last, the state the rig is in. min_record_s:
// the shortest record the next step may have (what the last step's verdict
// needs for its phasor target); the record is chosen from min_record_s·2^m
// up to max_record_s for the gain per second; extra_settle_s is added to
// every settle (a step found unsettled asks for it).
CandidateChoice ChooseNextStep(const PlannerFit& fit, const std::map<std::string, LevelSweep>& swept, int last_step,
                               const PlannerOptions& options, double min_record_s, double extra_settle_s,
                               const std::optional<PlanFocus>& focus = std::nullopt);

// The targets' σ and whether each reached it: the parameters of a fit
// against the options' targets.
std::vector<PlanParameter> TargetStatus(const ModelStructure& structure, const Eigen::MatrixXd& covariance,
                                        const PlannerOptions& options);

}  // namespace beamid::solver
