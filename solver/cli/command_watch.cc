// `beamid watch FOLDER`: follows a campaign folder while the acquisition
// writes it and, after every step, prints the step's verdict, the
// parameters so far and the next step, and rewrites the plan file the DAQ
// script polls (docs/watch.md, docs/test-plan-format.md). The work is
// workflow::WatchCampaign; this turns options into its request and prints.
#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include <fmt/core.h>

#include "hb/errors.h"
#include "hb/scenario.h"
#include "solver/cli/cli_output.h"
#include "solver/cli/command_registry.h"
#include "solver/workflow/watch_campaign.h"

namespace beamid::cli {
namespace {

struct WatchCommandOptions {
  workflow::WatchRequest request;
  std::vector<std::string> levels;      // LABEL=FORCE_N
  std::vector<double> band_hz;          // LOW HIGH
  std::vector<std::string> targets;     // parameter names
  std::vector<std::string> target_std;  // NAME=SIGMA
};

std::pair<std::string, double> LabelAndValue(const std::string& text, const std::string& option) {
  const auto at = text.find('=');
  double value = std::numeric_limits<double>::quiet_NaN();
  if (at != std::string::npos && at > 0) {
    try {
      std::size_t used = 0;
      value = std::stod(text.substr(at + 1), &used);
      if (used != text.size() - at - 1) value = std::numeric_limits<double>::quiet_NaN();
    } catch (const std::exception&) {
    }
  }
  if (!std::isfinite(value))
    throw InputError(option + " " + text + ": expected NAME=NUMBER. Fix: give e.g. " + option +
                         (option == "--level" ? " low=1.0 (the force amplitude in N)" : " k1=0.5 (σ in its unit)"));
  return {text.substr(0, at), value};
}

std::string Sigma(const solver::PlanParameter& p) {
  std::string text = fmt::format("{} = {:.5g} ± {:.2g} {}", p.name, p.value, p.std, p.unit);
  if (p.target_std > 0.0)
    text += p.std <= p.target_std ? fmt::format(" (target {:.2g}: reached)", p.target_std)
                                  : fmt::format(" (target {:.2g})", p.target_std);
  return text;
}

std::string DiagnosisLines(const solver::PlanDiagnosis& d) {
  std::string text = fmt::format("  diagnosis of {} steps ({:.1f} s): {}: {}\n", d.steps, d.seconds, d.verdict,
                                 fmt::join(d.selected, ", "));
  if (d.model_extended) text += "  the identification now holds it\n";
  if (!d.focus_level.empty())
    text += fmt::format("  measuring where they differ most: {} between {:.2f} and {:.2f} Hz\n", d.focus_level,
                        d.focus_low_hz, d.focus_high_hz);
  return text;
}

void PrintUpdate(const solver::LiveUpdate& update) {
  std::string line = fmt::format("step {:<28}", update.file);
  if (update.verdict) {
    const solver::StepVerdict& v = *update.verdict;
    line += fmt::format(" {} SNR {:.0f} dB, σ/|X1| {:.1e} ({})", update.usable ? "usable," : "REJECTED,", v.snr_db,
                        v.relative_std, v.worst_channel);
  } else {
    line += " FAULTY";
  }
  line += fmt::format("  [extract {:.2f} s, fit {:.2f} s, plan {:.2f} s]\n", update.extract_s, update.fit_s,
                      update.plan_s);
  if (!update.error.empty()) line += "  problem: " + update.error + "\n";
  if (update.verdict)
    for (const std::string& reason : update.verdict->reasons) line += "  again: " + reason + "\n";
  const solver::TestPlan& plan = update.plan;
  for (const solver::PlanParameter& p : plan.parameters)
    if (p.target_std > 0.0) line += "  " + Sigma(p) + "\n";
  if (!plan.parameters.empty()) line += fmt::format("  fit: {}\n", plan.fit_verdict);
  for (const std::string& warning : plan.warnings) line += "  warning: " + warning + "\n";
  if (update.diagnosed && plan.diagnosis) line += DiagnosisLines(*plan.diagnosis);
  if (plan.next)
    line += fmt::format("  next: {} ({:g} N) at {:.3f} Hz, settle {:.2f} s, record {:.2f} s: {}\n", plan.next->level,
                        plan.next->force_N, plan.next->frequency_hz, plan.next->settle_s, plan.next->record_s,
                        plan.next->reason);
  else
    line += "  done: " + plan.done_reason + "\n";
  PrintToStderr(line);
}

void RunWatch(WatchCommandOptions& options, const GlobalOptions& global) {
  workflow::WatchRequest& request = options.request;
  solver::PlannerOptions& planner = request.live.planner;
  for (const std::string& level : options.levels) {
    const auto [label, force] = LabelAndValue(level, "--level");
    planner.levels.push_back({.label = label, .force_N = force});
  }
  if (!options.band_hz.empty()) {
    planner.band_low_hz = options.band_hz[0];
    planner.band_high_hz = options.band_hz[1];
  }
  // A virtual rig's scenario gives what the command line leaves out: its
  // levels and its band.
  if (!request.virtual_rig.empty() && (planner.levels.empty() || options.band_hz.empty())) {
    const hb::Scenario scenario = hb::ReadScenario(request.virtual_rig);
    double low = INFINITY, high = -INFINITY;
    for (const hb::ScenarioLevel& level : scenario.levels) {
      if (options.levels.empty()) planner.levels.push_back({.label = level.label, .force_N = level.force_amplitude_N});
      for (const double f : level.frequencies_hz) {
        low = std::min(low, f);
        high = std::max(high, f);
      }
    }
    if (options.band_hz.empty() && std::isfinite(low)) {
      planner.band_low_hz = low;
      planner.band_high_hz = high;
    }
  }
  if (planner.levels.empty())
    throw InputError("--level: no force level given. Fix: give each level the rig may use, e.g. --level low=1 "
                         "--level high=9 (force amplitudes in N)");
  if (planner.band_low_hz <= 0.0)
    throw InputError("--band: not given. Fix: give the band each level is swept through, e.g. --band 50 58 (Hz)");
  if (!options.targets.empty()) planner.targets = options.targets;
  for (const std::string& text : options.target_std) {
    const auto [name, sigma] = LabelAndValue(text, "--target-std");
    planner.target_std[name] = sigma;
  }
  const bool print = !global.quiet && !global.JsonProgress();
  workflow::RunObserver observer = CliObserver(global);
  if (print)
    PrintToStderr(fmt::format("watching {}; the plan goes to {}{}\n", request.campaign_folder, request.plan_file,
                              request.virtual_rig.empty() ? "" : " (virtual rig: " + request.virtual_rig + ")"));
  const workflow::WatchOutcome outcome =
      workflow::WatchCampaign(request, observer, [&](const solver::LiveUpdate& update) {
        if (print) PrintUpdate(update);
      });
  if (!global.quiet) {
    std::string summary = outcome.idle_timeout
                              ? fmt::format("stopped: no step completed for {:g} s\n", request.idle_timeout_s)
                              : "done: " + outcome.plan.done_reason + "\n";
    summary += fmt::format("{} steps analysed; rig time asked for: {:.1f} s", outcome.plan.steps_analysed,
                           outcome.plan.rig_time_s);
    if (outcome.rig_steps > 0)
      summary += fmt::format(" (virtual rig: {} steps, {:.1f} s of settle + record)", outcome.rig_steps,
                             outcome.rig_time_s);
    PrintToStderr(summary + "\n");
    PrintToStderr("model: " + outcome.plan.model + "; 95 % intervals: " + outcome.plan.intervals + "\n");
    for (const solver::PlanParameter& p : outcome.plan.parameters)
      PrintToStderr(fmt::format("  {}  (95 %: {:.6g} … {:.6g}{})\n", Sigma(p), p.lower_95, p.upper_95,
                                p.depends_on_damping_law ? ", depends on the beam's damping law" : ""));
    if (outcome.plan.diagnosis) PrintToStderr(DiagnosisLines(*outcome.plan.diagnosis));
  }
}

BEAMID_REGISTER_COMMAND("watch", [](CLI::App& app, const GlobalOptions& global) {
  auto options = std::make_shared<WatchCommandOptions>();
  workflow::WatchRequest& request = options->request;
  solver::LiveOptions& live = request.live;
  CLI::App* command = app.add_subcommand(
      "watch",
      "Follow a campaign folder while the acquisition writes it: judge each step as it completes (settled, SNR,\n"
      "a jump), refit the support from the last optimum, and plan the next step (frequency, level, settle and\n"
      "record time) for what it teaches; the plan is rewritten after every step for the DAQ script to poll\n"
      "(docs/watch.md, docs/test-plan-format.md). With --virtual-rig the simulator is the rig (closed loop).\n\n"
      "Examples:\n"
      "  beamid watch acquisition/ --level low=1 --level mid=4 --level high=9 --band 50 58 --plan plan.json\n"
      "  beamid watch out/guided --virtual-rig examples/scenarios/paper_base.json --plan out/plan.json");
  command->add_option("folder", request.campaign_folder, "Campaign folder being written (campaign.json + steps)")
      ->required();
  command->add_option("--plan", request.plan_file, "Plan file written after every step (JSON)")
      ->capture_default_str()
      ->check(NonEmptyPath());
  command->add_option("--level", options->levels, "A force level the rig may use: LABEL=FORCE_N (repeatable)");
  command
      ->add_option("--band", options->band_hz,
                   "The band each level is swept through (up, or down for a softening support) [Hz]: LOW HIGH")
      ->expected(2)
      ->check(FiniteRange(1e-3, 1e6));
  command->add_option("--fit", live.fit_channels, "Response channels to fit (default: every sensor not ignored)");
  command->add_option("--target", options->targets, "Parameters the test is for (default: k1 k3 c)");
  command->add_option("--target-std", options->target_std, "σ a target must reach: NAME=SIGMA, in its unit");
  command->add_option("--target-relative", live.planner.target_relative_std,
                      "σ relative to its value for a target without --target-std")
      ->capture_default_str();
  command->add_option("--resolution", live.planner.resolution_hz, "Frequency grid of the candidate steps [Hz]")
      ->capture_default_str();
  command->add_option("--max-step", live.planner.max_step_hz, "Largest step ahead on a level [Hz]")
      ->capture_default_str();
  command->add_option("--max-steps", live.planner.max_steps, "Most steps the test may take")->capture_default_str();
  command->add_option("--settle", live.initial_settle_s, "Settle time of the first step [s]")->capture_default_str();
  command->add_option("--record", live.initial_record_s, "Record length of the first step [s]")->capture_default_str();
  command->add_option("--settle-tolerance", live.planner.settle_tolerance,
                      "Transient left when recording, relative to the response; sets each settle time")
      ->capture_default_str();
  command->add_option("--min-record", live.verdict.min_record_s, "Shortest record [s]")->capture_default_str();
  command->add_option("--max-record", live.planner.max_record_s, "Longest record the plan may ask for [s]")
      ->capture_default_str();
  command->add_option("--phasor-target", live.verdict.target_relative_std,
                      "σ/|X1| a step's worst channel should reach; sets the record length")
      ->capture_default_str();
  command->add_flag("--modal-loss-factor", live.modal_loss_factor,
                   "Fit the beam's damping as the modal loss factor (the law of time-domain codes) instead of "
                   "E(1 + i eta)");
  command->add_option("--stable", request.follower.stable_s, "A file unchanged this long [s] is complete")
      ->capture_default_str();
  command->add_option("--poll", request.poll_s, "Seconds between looks at the folder")->capture_default_str();
  command->add_option("--idle-timeout", request.idle_timeout_s, "Stop when no step completes for this long [s]")
      ->capture_default_str();
  command->add_option("--virtual-rig", request.virtual_rig,
                      "Scenario file: the time-domain simulator runs each planned step into the folder")
      ->check(CLI::ExistingFile);
  command->callback([options, &global] { RunWatch(*options, global); });
});

}  // namespace
}  // namespace beamid::cli
