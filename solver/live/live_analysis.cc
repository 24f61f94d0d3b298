#include "solver/live/live_analysis.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>
#include <utility>

#include <fmt/format.h>

#include "hb/errors.h"
#include "hb/option_checks.h"
#include "hb/support_law.h"
#include "solver/diagnosis/candidate_physics.h"
#include "solver/diagnosis/diagnosis.h"
#include "solver/estimation/damping_laws.h"

namespace beamid::solver {

void LiveOptions::Validate() const {
  using option_checks::RequireInRange;
  RequireInRange("harmonics", harmonics, 1, option_checks::kMaxHarmonics);
  RequireInRange("fit_harmonics", fit_harmonics, 1, harmonics);
  estimator.Validate();
  verdict.Validate();
  planner.Validate();
  RequireInRange("min_steps_to_fit", min_steps_to_fit, 2, 100000);
  RequireInRange("--settle", initial_settle_s, planner.min_settle_s, planner.max_settle_s);
  RequireInRange("--record", initial_record_s, verdict.min_record_s, verdict.max_record_s);
}

namespace {

double SecondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

const PlanLevel* FindLevel(const PlannerOptions& planner, const std::string& label) {
  for (const PlanLevel& level : planner.levels)
    if (level.label == label) return &level;
  return nullptr;
}

int LevelRank(const PlannerOptions& planner, const std::string& label) {
  for (std::size_t i = 0; i < planner.levels.size(); ++i)
    if (planner.levels[i].label == label) return static_cast<int>(i);
  return static_cast<int>(planner.levels.size());
}

}  // namespace

LiveAnalysis::LiveAnalysis(const LiveOptions& options) : options_(options) {
  options_.Validate();
  options_.estimator.num_harmonics = std::max(options_.estimator.num_harmonics, options_.fit_harmonics);
  phasors_.num_harmonics = options_.estimator.num_harmonics;
  structure_ = PolynomialModel({.k1_Nm_rad = 100.0});
  // The beam's own damping is unknown in a real test: fitted, as identify does.
  structure_.linear.push_back(options_.modal_loss_factor ? ModalLossFactor(1e-4) : LossFactor(1e-4));
  model_harmonics_ = options_.harmonics;
  settle_s_ = options_.initial_settle_s;
  record_s_ = options_.initial_record_s;
  LiveUpdate first;
  Plan(first, std::nullopt);
  plan_ = first.plan;
}

void LiveAnalysis::NoteSwept(const std::string& level, double frequency_hz) {
  const SweepDirection planned =
      plan_.next && plan_.next->level == level ? plan_.next->sweep : SweepDirection::kUp;
  const auto [sweep, first] = swept_.try_emplace(level, LevelSweep{.last_hz = frequency_hz, .direction = planned});
  if (first) return;
  double& last = sweep->second.last_hz;
  last = sweep->second.direction == SweepDirection::kDown ? std::min(last, frequency_hz) : std::max(last, frequency_hz);
}

double LiveAnalysis::RepeatSettle() const {
  // The settle the step was planned with (or the bootstrap's), as a floor.
  return std::max(settle_s_, plan_.next ? plan_.next->settle_s : 0.0);
}

PlannedStep LiveAnalysis::SweepStep() const {
  const PlannerOptions& planner = options_.planner;
  for (const PlanLevel& level : planner.levels) {
    const auto last = swept_.find(level.label);
    const SweepDirection direction = last == swept_.end() ? SweepDirection::kUp : last->second.direction;
    const bool down = direction == SweepDirection::kDown;
    const double f = last == swept_.end() ? planner.band_low_hz
                                          : last->second.last_hz + (down ? -1.0 : 1.0) * planner.max_step_hz;
    if (f > planner.band_high_hz + 1e-9 || f < planner.band_low_hz - 1e-9) continue;
    return PlannedStep{.level = level.label,
                       .force_N = level.force_N,
                       .frequency_hz = f,
                       .settle_s = settle_s_,
                       .record_s = record_s_,
                       .reason = fmt::format("sweeping {} {} in steps of {:g} Hz until {} usable steps allow a fit",
                                             level.label, down ? "downwards" : "upwards", planner.max_step_hz,
                                             options_.min_steps_to_fit),
                       .sweep = direction};
  }
  return {};
}

void LiveAnalysis::Plan(LiveUpdate& update, const std::optional<PlannedStep>& repeat) {
  const auto start = std::chrono::steady_clock::now();
  TestPlan plan;
  plan.sequence = plan_.sequence + 1;
  plan.steps_analysed = static_cast<int>(phasors_.steps.size());
  plan.rig_time_s = plan_.rig_time_s;
  plan.model = model_name_;
  plan.intervals = "statistical (value ± 1.96σ)";
  plan.diagnosis = diagnosis_;
  if (fit_) {
    plan.parameters = TargetStatus(structure_, fit_->covariance, options_.planner);
    plan.reduced_chi_square = fit_->reduced_chi_square;
    plan.fit_verdict = fit_->verdict.text;
    if (!fit_->verdict.within_noise)
      plan.warnings.push_back("the model misses the data beyond their noise: its σ are not to be trusted; run "
                              "beamid diagnose on the campaign so far");
  }
  if (update.verdict)
    for (const std::string& warning : update.verdict->warnings) plan.warnings.push_back(warning);
  if (!update.fit_error.empty()) plan.warnings.push_back("the fit failed: " + update.fit_error);
  if (!update.error.empty() && !repeat) plan.warnings.push_back(update.file + " left out: " + update.error);

  bool precise = fit_.has_value() && fit_->verdict.within_noise;
  for (const PlanParameter& p : plan.parameters)
    if (p.target_std > 0.0 && !(p.std <= p.target_std)) precise = false;
  if (repeat) {
    plan.next = repeat;
  } else if (precise) {
    plan.done = true;
    plan.done_reason = "every target parameter has reached its σ and the model fits within the noise";
  } else if (plan.steps_analysed >= options_.planner.max_steps) {
    plan.done = true;
    plan.done_reason = fmt::format("{} steps analysed, the most the plan allows", plan.steps_analysed);
  } else if (!fit_) {
    PlannedStep sweep = SweepStep();
    if (sweep.level.empty()) {
      plan.done = true;
      plan.done_reason = "every level was swept without a fit being possible";
    } else {
      plan.next = sweep;
    }
  } else {
    const PlannerFit planner_fit{.data = &data_,
                                 .family = &HarmonicBalanceFamily(),
                                 .structure = &structure_,
                                 .model = {.num_harmonics = model_harmonics_},
                                 .covariance = fit_->covariance,
                                 .analysed_s = analysed_s_,
                                 .within_noise = fit_->verdict.within_noise};
    int last_step = 0;
    for (std::size_t i = 0; i < data_.steps.size(); ++i)
      if (data_.steps[i].level == last_level_ && data_.steps[i].nominal_frequency_hz == last_frequency_hz_)
        last_step = static_cast<int>(i);
    CandidateChoice choice =
        ChooseNextStep(planner_fit, swept_, last_step, options_.planner, record_s_, extra_settle_s_, focus_);
    if (!choice.step && focus_) {
      // The band where the causes differ is measured: diagnose again at the
      // next step, and plan as before meanwhile.
      focus_.reset();
      choice = ChooseNextStep(planner_fit, swept_, last_step, options_.planner, record_s_, extra_settle_s_);
    }
    if (choice.step) {
      plan.next = choice.step;
    } else {
      plan.done = true;
      plan.done_reason = choice.why_none;
    }
  }
  if (plan.next) plan.rig_time_s += plan.next->settle_s + plan.next->record_s;
  if (plan.done && fit_ && fit_->verdict.within_noise) AddModelFormIntervals(plan);
  update.plan_s = SecondsSince(start);
  update.plan = plan;
  plan_ = std::move(plan);
}

void LiveAnalysis::AddModelFormIntervals(TestPlan& plan) const {
  // The beam's damping law is assumed: refitted under the others, as
  // `beamid identify` does, the parameters get the intervals that law does
  // not decide (near resonance, where the plan measures most, the laws split
  // the beam's loss and the support's c differently).
  IdentifyOptions identify;
  identify.model.num_harmonics = model_harmonics_;
  identify.num_workers = 1;
  const DampingLawEnvelope envelope = FitDampingLaws(data_, structure_, *fit_, identify);
  if (envelope.empty()) return;
  plan.intervals = TotalIntervalParts(envelope);
  for (PlanParameter& p : plan.parameters)
    for (const ModelFormInterval& interval : envelope.intervals)
      if (interval.name == p.name) {
        p.lower_95 = interval.lower_95;
        p.upper_95 = interval.upper_95;
        p.depends_on_damping_law = interval.depends_on_damping_law;
      }
}

void LiveAnalysis::Refit(const signal::Campaign& campaign, LiveUpdate& update) {
  const auto start = std::chrono::steady_clock::now();
  try {
    data_ = MakeFitData(campaign, phasors_,
                        {.channels = fit_channels_,
                         .num_fit_harmonics = options_.fit_harmonics,
                         .uncertainty = PhasorUncertainty::kPropagated});
    IdentifyOptions identify;
    identify.model.num_harmonics = model_harmonics_;
    identify.num_starts = 0;
    identify.num_workers = 1;
    // From the previous optimum: a step moves it little, and the direct
    // estimate's start needs ~400 iterations where this needs a few.
    identify.use_direct_estimate = !structure_fitted_;
    std::optional<IdentifyResult> result;
    std::string warm_error;
    try {
      result = Identify(data_, structure_, identify);
    } catch (const std::exception& e) {
      warm_error = e.what();
    }
    // A step on a level the model has not seen may move the optimum far
    // (another branch, physics the model lacks): the previous optimum is
    // then a poor start, and a fit from the data's own direct estimate, and
    // from starts around it, may find what it did not.
    const bool poor = !result || (fit_ && result->reduced_chi_square > 10.0 * std::max(1.0, fit_->reduced_chi_square));
    if (poor && identify.use_direct_estimate == false &&
        dynamic_cast<const hb::PolynomialSupportLaw*>(structure_.law.get()) != nullptr) {
      identify.use_direct_estimate = true;
      identify.num_starts = 4;
      identify.num_workers = 0;
      try {
        IdentifyResult fresh = Identify(data_, structure_, identify);
        if (!result || fresh.chi_square < result->chi_square) result = std::move(fresh);
      } catch (const std::exception&) {
        if (!result) throw;
      }
    }
    if (!result) throw std::runtime_error(warm_error);
    std::vector<double> values;
    for (const ParameterEstimate& p : result->parameters) values.push_back(p.value);
    structure_.SetValues(values);
    structure_fitted_ = true;
    fit_ = std::move(result);
    update.refitted = true;
  } catch (const std::exception& e) {
    update.fit_error = e.what();
  }
  update.fit_s = SecondsSince(start);
}

void LiveAnalysis::Diagnose(const signal::Campaign& campaign, LiveUpdate& update) {
  const int steps = static_cast<int>(phasors_.steps.size());
  const bool misfit = fit_ && !fit_->verdict.within_noise;
  const bool due = options_.diagnose && misfit && steps >= options_.min_steps_to_diagnose &&
                   (!diagnosis_ || (steps - diagnosis_->steps >= options_.diagnose_every && !focus_));
  if (!due) return;
  const auto start = std::chrono::steady_clock::now();
  PlanDiagnosis found{.steps = steps};
  try {
    const FitData located = MakeFitData(campaign, phasors_,
                                        {.channels = fit_channels_,
                                         .num_fit_harmonics = std::max(5, options_.fit_harmonics),
                                         .uncertainty = PhasorUncertainty::kPropagated});
    DiagnosisOptions options;
    options.model_harmonics = options_.harmonics;
    options.modal_loss_factor = options_.modal_loss_factor;
    options.num_workers = options_.diagnosis_workers;
    options.damping_laws = false;
    // The physics only: a step the recording spoilt is measured again by its
    // verdict, and with few steps of a level the model cannot follow, each
    // of them looks like an outlying step.
    options.measurement_artefacts = false;
    const DiagnosisResult result = solver::Diagnose(data_, FitData{}, located, options);
    found.verdict = ToString(result.verdict);
    found.selected = result.selected;
    found.summary = result.summary;
    if (result.verdict == DiagnosisVerdict::kCausesIndistinguishable && result.suggestion) {
      const MeasurementSuggestion& suggestion = *result.suggestion;
      const auto most = std::max_element(suggestion.levels.begin(), suggestion.levels.end(),
                                         [](const LevelShare& a, const LevelShare& b) { return a.share < b.share; });
      if (most != suggestion.levels.end() && FindLevel(options_.planner, most->level)) {
        focus_ = PlanFocus{
            .level = most->level, .low_hz = suggestion.focus_low_hz, .high_hz = suggestion.focus_high_hz};
        found.focus_level = focus_->level;
        found.focus_low_hz = focus_->low_hz;
        found.focus_high_hz = focus_->high_hz;
      }
    }
    const bool named = result.verdict == DiagnosisVerdict::kCauseNamed ||
                       result.verdict == DiagnosisVerdict::kCombinationNamed;
    if (named && result.blame == Blame::kModel && model_name_ == "polynomial support") {
      // The named physics joins the identification: each cause extends the
      // base as the diagnosis did, at the values of its final fit.
      ModelStructure extended = structure_;
      int harmonics = model_harmonics_;
      for (const std::string& name : result.selected)
        for (const CandidatePhysics& physics : CandidateLibrary())
          if (physics.name == name) {
            const CandidateExtension extension =
                physics.extend(extended, {.data = &data_, .model_harmonics = harmonics});
            extended = extension.structure;
            harmonics = std::max(harmonics, extension.model_harmonics);
          }
      std::vector<double> values;
      std::vector<std::string> names;
      for (const ParameterEstimate& p : result.final_fit.parameters) {
        values.push_back(p.value);
        names.push_back(p.name);
      }
      if (names == extended.Names()) {
        extended.SetValues(values);
        structure_ = extended;
        model_harmonics_ = harmonics;
        model_name_ = "polynomial support with " + fmt::format("{}", fmt::join(result.selected, " and "));
        found.model_extended = true;
        Refit(campaign, update);  // from the diagnosis's final fit
      }
    }
  } catch (const std::exception& e) {
    found.verdict = "failed";
    found.summary = std::string("the diagnosis failed: ") + e.what();
  }
  found.seconds = SecondsSince(start);
  update.diagnose_s = found.seconds;
  update.diagnosed = true;
  diagnosis_ = found;
}

LiveUpdate LiveAnalysis::Add(const signal::FollowedStep& step, const signal::Campaign& campaign) {
  if (fit_channels_.empty()) {
    if (options_.fit_channels.empty()) {
      for (const signal::ChannelSpec& sensor : campaign.sensors)
        if (campaign.Use(sensor.channel) != signal::ChannelUse::kIgnored) fit_channels_.push_back(sensor.channel);
    } else {
      fit_channels_ = options_.fit_channels;
    }
    phasors_.campaign = campaign.name;
  }
  LiveUpdate update{.index = step.index, .file = step.step.file};
  const PlanLevel* level = FindLevel(options_.planner, step.step.level);
  const auto again = [&](const std::string& why) {
    PlannedStep repeat{.level = step.step.level,
                       .force_N = level ? level->force_N : 0.0,
                       .frequency_hz = step.step.frequency_hz,
                       .settle_s = settle_s_,
                       .record_s = record_s_,
                       .reason = "measure " + step.step.file + " again: " + why,
                       .repeat = true};
    Plan(update, repeat);
    return update;
  };
  // A step that fails the same way take after take is a property of the
  // beam or the rig, not bad luck: after max_repeats more takes the test
  // moves on (leaving the step out, or using it with a warning).
  const bool last_take = ++failed_takes_[{step.step.level, step.step.frequency_hz}] > options_.max_repeats;
  const auto leave_out = [&] {
    NoteSwept(step.step.level, step.step.frequency_hz);
    Plan(update, std::nullopt);
    return update;
  };
  if (!level) {
    update.error = "its level \"" + step.step.level + "\" is none of the plan's levels";
    Plan(update, std::nullopt);
    return update;
  }
  if (step.status == signal::FollowedStatus::kFaulty) {
    update.error = step.error;
    return last_take ? leave_out() : again(step.error);
  }
  const auto start = std::chrono::steady_clock::now();
  signal::Campaign analysed = campaign;
  analysed.Analyse(fit_channels_);
  signal::StepPhasors phasors;
  try {
    phasors = signal::EstimateStepPhasors(step.recording, analysed, step.step, options_.estimator);
  } catch (const std::exception& e) {
    update.extract_s = SecondsSince(start);
    update.error = e.what();
    if (last_take) return leave_out();
    // No steady state: most often too short a settle.
    settle_s_ = std::min(options_.planner.max_settle_s, 2.0 * RepeatSettle());
    return again(update.error);
  }
  // The step before on the level's sweep: the nearest below going up, above going down.
  const auto begun = swept_.find(phasors.level);
  const double sign = begun != swept_.end() && begun->second.direction == SweepDirection::kDown ? -1.0 : 1.0;
  const signal::StepPhasors* previous = nullptr;
  for (const signal::StepPhasors& other : phasors_.steps)
    if (other.level == phasors.level && sign * other.nominal_frequency_hz < sign * phasors.nominal_frequency_hz &&
        (!previous || sign * other.nominal_frequency_hz > sign * previous->nominal_frequency_hz))
      previous = &other;
  update.verdict = JudgeStep(phasors, fit_channels_, options_.verdict, previous);
  update.extract_s = SecondsSince(start);
  StepVerdict& verdict = *update.verdict;
  if (verdict.measure_again && last_take) {
    for (const std::string& reason : verdict.reasons)
      verdict.warnings.push_back(fmt::format("used after {} takes although {}", options_.max_repeats + 1, reason));
  } else if (verdict.measure_again) {
    settle_s_ = std::min(options_.planner.max_settle_s, RepeatSettle() + verdict.extra_settle_s);
    if (phasors.quality.unsettled) extra_settle_s_ += verdict.extra_settle_s;
    std::string why;
    for (const std::string& reason : verdict.reasons) why += (why.empty() ? "" : "; ") + reason;
    return again(why);
  }
  update.usable = true;
  // A step measured again replaces its take before.
  const auto same = std::find_if(phasors_.steps.begin(), phasors_.steps.end(), [&](const signal::StepPhasors& s) {
    return s.level == phasors.level && std::abs(s.nominal_frequency_hz - phasors.nominal_frequency_hz) < 1e-9;
  });
  if (same != phasors_.steps.end()) {
    analysed_s_.erase(analysed_s_.begin() + (same - phasors_.steps.begin()));
    phasors_.steps.erase(same);
  }
  // Level by level, each upwards: the order the fit's continuation follows.
  const auto before = [&](const signal::StepPhasors& a, double analysed_a, const signal::StepPhasors& b,
                          double analysed_b) {
    const int ra = LevelRank(options_.planner, a.level), rb = LevelRank(options_.planner, b.level);
    if (ra != rb) return ra < rb;
    if (a.nominal_frequency_hz != b.nominal_frequency_hz) return a.nominal_frequency_hz < b.nominal_frequency_hz;
    return analysed_a < analysed_b;
  };
  std::size_t at = 0;
  while (at < phasors_.steps.size() && before(phasors_.steps[at], analysed_s_[at], phasors, verdict.analysed_s)) ++at;
  phasors_.steps.insert(phasors_.steps.begin() + static_cast<std::ptrdiff_t>(at), phasors);
  analysed_s_.insert(analysed_s_.begin() + static_cast<std::ptrdiff_t>(at), verdict.analysed_s);
  NoteSwept(phasors.level, phasors.nominal_frequency_hz);
  last_level_ = phasors.level;
  last_frequency_hz_ = phasors.nominal_frequency_hz;
  record_s_ = verdict.record_needed_s;
  if (static_cast<int>(phasors_.steps.size()) >= options_.min_steps_to_fit) Refit(analysed, update);
  Diagnose(analysed, update);
  Plan(update, std::nullopt);
  return update;
}

}  // namespace beamid::solver
