#include "solver/live/live_analysis.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>
#include <utility>

#include <fmt/format.h>

#include "hb/errors.h"
#include "hb/option_checks.h"

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
  structure_.linear.push_back(LossFactor(1e-4));
  settle_s_ = options_.initial_settle_s;
  record_s_ = options_.initial_record_s;
  LiveUpdate first;
  Plan(first, std::nullopt);
  plan_ = first.plan;
}

double LiveAnalysis::RepeatSettle() const {
  // The settle the step was planned with (or the bootstrap's), as a floor.
  return std::max(settle_s_, plan_.next ? plan_.next->settle_s : 0.0);
}

PlannedStep LiveAnalysis::SweepStep() const {
  const PlannerOptions& planner = options_.planner;
  for (const PlanLevel& level : planner.levels) {
    const auto last = last_hz_.find(level.label);
    const double f = last == last_hz_.end() ? planner.band_low_hz : last->second + planner.max_step_hz;
    if (f > planner.band_high_hz + 1e-9) continue;
    return PlannedStep{.level = level.label,
                       .force_N = level.force_N,
                       .frequency_hz = f,
                       .settle_s = settle_s_,
                       .record_s = record_s_,
                       .reason = fmt::format(
                           "sweeping {} upwards in steps of {:g} Hz until {} usable steps allow a fit", level.label,
                           planner.max_step_hz, options_.min_steps_to_fit)};
  }
  return {};
}

void LiveAnalysis::Plan(LiveUpdate& update, const std::optional<PlannedStep>& repeat) {
  const auto start = std::chrono::steady_clock::now();
  TestPlan plan;
  plan.sequence = plan_.sequence + 1;
  plan.steps_analysed = static_cast<int>(phasors_.steps.size());
  plan.rig_time_s = plan_.rig_time_s;
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
                                 .model = {.num_harmonics = options_.harmonics},
                                 .covariance = fit_->covariance,
                                 .analysed_s = analysed_s_};
    int last_step = 0;
    for (std::size_t i = 0; i < data_.steps.size(); ++i)
      if (data_.steps[i].level == last_level_ && data_.steps[i].nominal_frequency_hz == last_frequency_hz_)
        last_step = static_cast<int>(i);
    CandidateChoice choice =
        ChooseNextStep(planner_fit, last_hz_, last_step, options_.planner, record_s_, extra_settle_s_);
    if (choice.step) {
      plan.next = choice.step;
    } else {
      plan.done = true;
      plan.done_reason = choice.why_none;
    }
  }
  if (plan.next) plan.rig_time_s += plan.next->settle_s + plan.next->record_s;
  update.plan_s = SecondsSince(start);
  update.plan = plan;
  plan_ = std::move(plan);
}

void LiveAnalysis::Refit(const signal::Campaign& campaign, LiveUpdate& update) {
  const auto start = std::chrono::steady_clock::now();
  try {
    data_ = MakeFitData(campaign, phasors_,
                        {.channels = fit_channels_,
                         .num_fit_harmonics = options_.fit_harmonics,
                         .uncertainty = PhasorUncertainty::kPropagated});
    IdentifyOptions identify;
    identify.model.num_harmonics = options_.harmonics;
    identify.num_starts = 0;
    identify.num_workers = 1;
    // From the previous optimum: a step moves it little, and the direct
    // estimate's start needs ~400 iterations where this needs a few.
    identify.use_direct_estimate = !fit_.has_value();
    IdentifyResult result = Identify(data_, structure_, identify);
    std::vector<double> values;
    for (const ParameterEstimate& p : result.parameters) values.push_back(p.value);
    structure_.SetValues(values);
    fit_ = std::move(result);
    update.refitted = true;
  } catch (const std::exception& e) {
    update.fit_error = e.what();
  }
  update.fit_s = SecondsSince(start);
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
  if (!level) {
    update.error = "its level \"" + step.step.level + "\" is none of the plan's levels";
    Plan(update, std::nullopt);
    return update;
  }
  if (step.status == signal::FollowedStatus::kFaulty) {
    update.error = step.error;
    return again(step.error);
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
    // No steady state: most often too short a settle.
    settle_s_ = std::min(options_.planner.max_settle_s, 2.0 * RepeatSettle());
    return again(update.error);
  }
  const signal::StepPhasors* previous = nullptr;
  for (const signal::StepPhasors& other : phasors_.steps)
    if (other.level == phasors.level && other.nominal_frequency_hz < phasors.nominal_frequency_hz &&
        (!previous || other.nominal_frequency_hz > previous->nominal_frequency_hz))
      previous = &other;
  update.verdict = JudgeStep(phasors, fit_channels_, options_.verdict, previous);
  update.extract_s = SecondsSince(start);
  const StepVerdict& verdict = *update.verdict;
  if (verdict.measure_again) {
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
  double& last = last_hz_.try_emplace(phasors.level, phasors.nominal_frequency_hz).first->second;
  last = std::max(last, phasors.nominal_frequency_hz);
  last_level_ = phasors.level;
  last_frequency_hz_ = phasors.nominal_frequency_hz;
  record_s_ = verdict.record_needed_s;
  if (static_cast<int>(phasors_.steps.size()) >= options_.min_steps_to_fit) Refit(analysed, update);
  Plan(update, std::nullopt);
  return update;
}

}  // namespace beamid::solver
