// A stepped-sine test analysed while it runs: each step the acquisition
// completes (signal/campaign_follower.h) is reduced to phasors, judged
// (step_verdict.h) and, when usable, added to the identification, which is
// refitted from its previous optimum (the first fit from the direct
// estimate, as `beamid identify`); then the next step is planned
// (next_step_planner.h): the same step again when it was faulty or
// unsettled (at most max_repeats times; then it is used with a warning, or
// left out); a plain upward sweep of the first level until a fit is
// possible; afterwards the most informative step, and its record length,
// per second of rig time, until the target parameters reach their σ with
// the fit within the noise, or nothing measurable remains. The last plan's
// intervals are then the model-form ones over the beam's damping laws, as
// `beamid identify` gives them (the loss factor law only).
// Before the first fit every step settles initial_settle_s; afterwards the
// planner times each candidate's settling by the fitted model's decay rate
// and the change it makes. A step that had not settled is measured again
// with the verdict's margin more, and every later settle keeps that margin.
// The record is at least what the last step needed for the target phasor σ.
//
// When the fit misses the steps beyond their noise (from
// min_steps_to_diagnose usable steps on, and again every diagnose_every
// steps while it still does), the diagnosis runs on the steps so far
// (solver/diagnosis/diagnosis.h): a cause of the model it names is added to
// the identification (its parameters beside k1..c, the plan's sensitivities
// from then on those of that model); when two causes fit alike, the plan
// measures where its measurement suggestion says they differ most (the
// level and band of most of the expected Δχ²) until that band is measured,
// then diagnoses again.
#pragma once

#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "signal/campaign.h"
#include "signal/campaign_follower.h"
#include "signal/phasor_estimator.h"
#include "signal/phasor_set.h"
#include "solver/estimation/fit_data.h"
#include "solver/estimation/identify.h"
#include "solver/estimation/model_structure.h"
#include "solver/live/next_step_planner.h"
#include "solver/live/step_verdict.h"
#include "solver/live/test_plan.h"

namespace beamid::solver {

struct LiveOptions {
  std::vector<std::string> fit_channels;  // empty: every sensor campaign.json does not ignore
  int harmonics = 5;                      // H of the model
  int fit_harmonics = 3;                  // K fitted
  signal::PhasorEstimatorOptions estimator;
  StepVerdictOptions verdict;
  PlannerOptions planner;
  int min_steps_to_fit = 5;     // usable steps before the first fit
  int max_repeats = 2;          // takes of a failing step after the first
  // The beam's damping as the modal loss factor η_m matched per mode at its
  // driving harmonic (hb/matched_modal_loss.h, the law of time-domain codes,
  // the simulator's among them) instead of E(1 + iη): the two split the
  // beam's loss and the support's c differently.
  bool modal_loss_factor = false;
  bool diagnose = true;
  int min_steps_to_diagnose = 8;
  int diagnose_every = 6;
  int diagnosis_workers = 0;  // worker processes of the diagnosis's refits (0: one per core)
  double initial_settle_s = 6.0;  // from rest, or 1 Hz on, near resonance: ln(1e5)/σ_d of the paper's beam is 5 s
  double initial_record_s = 0.5;

  // Throws InputError naming the field, its value and the allowed range.
  void Validate() const;
};

struct LiveUpdate {
  int index = 0;                       // the step's place in campaign.json
  std::string file;
  bool usable = false;                 // added to the identification
  std::string error;                   // a faulty recording: what is wrong
  std::optional<StepVerdict> verdict;  // when phasors could be extracted
  bool refitted = false;
  bool diagnosed = false;              // a diagnosis ran after this step (plan.diagnosis)
  std::string fit_error;               // a fit that failed (the plan keeps sweeping)
  TestPlan plan;
  double extract_s = 0.0, fit_s = 0.0, plan_s = 0.0;  // wall time of each part
  double diagnose_s = 0.0;
};

class LiveAnalysis {
 public:
  // Throws InputError for options out of range. The campaign is not needed
  // yet: the first plan is written before the acquisition has begun.
  explicit LiveAnalysis(const LiveOptions& options);

  // The plan before any step: the first level's first frequency.
  const TestPlan& plan() const { return plan_; }
  // One step handed out by the follower; `campaign` is the follower's
  // campaign.json as now (its steps grow while the test runs). Throws
  // InputError for a fit channel that is no sensor of the campaign.
  LiveUpdate Add(const signal::FollowedStep& step, const signal::Campaign& campaign);

  // The usable steps' phasors so far (a step measured again replaces the
  // take before), level by level, each level upwards in frequency.
  const signal::PhasorSet& phasors() const { return phasors_; }
  const std::optional<IdentifyResult>& fit() const { return fit_; }
  const ModelStructure& structure() const { return structure_; }

 private:
  void Refit(const signal::Campaign& campaign, LiveUpdate& update);
  void Diagnose(const signal::Campaign& campaign, LiveUpdate& update);
  void Plan(LiveUpdate& update, const std::optional<PlannedStep>& repeat);
  PlannedStep SweepStep() const;
  double RepeatSettle() const;
  void AddModelFormIntervals(TestPlan& plan) const;

  LiveOptions options_;
  std::vector<std::string> fit_channels_;  // set at the first step
  signal::PhasorSet phasors_;
  std::vector<double> analysed_s_;  // per phasors_ step
  FitData data_;
  ModelStructure structure_;
  bool structure_fitted_ = false;  // its values are a fit's: later fits start there
  std::optional<IdentifyResult> fit_;
  int model_harmonics_ = 5;
  std::string model_name_ = "polynomial support";
  std::optional<PlanDiagnosis> diagnosis_;
  std::optional<PlanFocus> focus_;
  // A step of `level` at `frequency_hz` was measured (or left out): the level's sweep moves past it. A level's
  // first step sets its way, the one the plan asked for.
  void NoteSwept(const std::string& level, double frequency_hz);
  std::map<std::string, LevelSweep> swept_;  // per level begun: its last usable step and its way
  std::map<std::pair<std::string, double>, int> failed_takes_;  // takes per level and frequency
  std::string last_level_;                 // the usable step measured last: the rig's state
  double last_frequency_hz_ = 0.0;
  double settle_s_ = 0.0;        // before the first fit, and for a step measured again
  double extra_settle_s_ = 0.0;  // what unsettled steps have added
  double record_s_ = 0.0;
  TestPlan plan_;
};

}  // namespace beamid::solver
