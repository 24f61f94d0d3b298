#include "solver/workflow/watch_campaign.h"

#include <chrono>
#include <filesystem>
#include <system_error>
#include <thread>

#include <fmt/format.h>

#include "hb/errors.h"
#include "hb/option_checks.h"
#include "hb/scenario.h"
#include "hb/virtual_rig.h"
#include "solver/live/test_plan_io.h"
#include "solver/workflow/output_paths.h"

namespace beamid::workflow {

void WatchRequest::Validate() const {
  using option_checks::RequireInRange;
  RequireInRange("--poll", poll_s, 1e-3, 3600.0);
  RequireInRange("--idle-timeout", idle_timeout_s, 0.0, 1e7);
  live.Validate();
  follower.Validate();
  // An acquisition writes into a folder that exists; waiting for one whose
  // name was mistyped would wait until the idle timeout. The virtual rig
  // makes its own.
  std::error_code error;
  if (virtual_rig.empty() && !std::filesystem::is_directory(campaign_folder, error))
    throw InputError(campaign_folder, "", "is no folder",
                     "create the campaign folder the acquisition writes into (or correct its name) before watching it");
  OutputPaths paths;
  paths.InputFolder(campaign_folder).Input(virtual_rig).Output("--plan", plan_file);
  paths.Check();
}

CampaignWatch::CampaignWatch(const WatchRequest& request)
    : request_(request), follower_(request.campaign_folder, request.follower), analysis_(request.live) {
  request_.Validate();
  solver::WriteTestPlan(request_.plan_file, analysis_.plan());
}

CampaignWatch::~CampaignWatch() = default;

std::vector<solver::LiveUpdate> CampaignWatch::Poll(double now_s) {
  std::vector<solver::LiveUpdate> updates;
  for (const signal::FollowedStep& step : follower_.Look(now_s)) {
    updates.push_back(analysis_.Add(step, *follower_.campaign()));
    solver::WriteTestPlan(request_.plan_file, analysis_.plan());
  }
  return updates;
}

namespace {

double Now() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

}  // namespace

WatchOutcome WatchCampaign(const WatchRequest& request, const RunObserver& observer,
                           const LiveUpdateCallback& on_update) {
  request.Validate();
  std::unique_ptr<hb::VirtualRig> rig;
  if (!request.virtual_rig.empty()) {
    try {
      rig = std::make_unique<hb::VirtualRig>(hb::ReadScenario(request.virtual_rig), request.campaign_folder);
    } catch (const InputError&) {
      throw;
    } catch (const std::invalid_argument& e) {  // the scenario's physics, which its reader does not check
      throw InputError(request.virtual_rig, "", e.what(), "correct the scenario (docs/simulator.md)");
    }
  }
  CampaignWatch watch(request);
  WatchOutcome outcome;
  // The virtual rig's clock: each step is written at once, so the follower
  // sees its file stable after one poll interval without anyone waiting.
  double virtual_now = 0.0;
  double last_step_s = rig ? 0.0 : Now();
  int last_sequence = -1;
  while (!watch.plan().done) {
    if (rig && watch.plan().sequence != last_sequence) {
      last_sequence = watch.plan().sequence;
      const solver::PlannedStep& next = *watch.plan().next;
      observer.Note(fmt::format("rig: {} at {:.3f} Hz, settle {:.2f} s, record {:.2f} s", next.level,
                                next.frequency_hz, next.settle_s, next.record_s));
      try {
        rig->Run(next.level, next.frequency_hz, next.settle_s, next.record_s);
      } catch (const std::invalid_argument& e) {
        throw InputError(request.virtual_rig, "", std::string("the rig cannot run the planned step: ") + e.what(),
                             "give the scenario the plan's levels");
      }
    }
    const double now = rig ? (virtual_now += request.poll_s + request.follower.stable_s) : Now();
    const std::vector<solver::LiveUpdate> updates = watch.Poll(now);
    outcome.steps_handed_out += static_cast<int>(updates.size());
    for (const solver::LiveUpdate& update : updates)
      if (on_update) on_update(update);
    if (!updates.empty()) last_step_s = now;
    if (!rig) {
      if (request.idle_timeout_s > 0.0 && now - last_step_s > request.idle_timeout_s) {
        outcome.idle_timeout = true;
        break;
      }
      std::this_thread::sleep_for(std::chrono::duration<double>(request.poll_s));
    } else if (updates.empty() && now - last_step_s > 100.0 * (request.poll_s + request.follower.stable_s)) {
      throw std::runtime_error("the virtual rig wrote a step that the watch never saw complete");
    }
  }
  if (rig) {
    rig->Finish();
    outcome.rig_time_s = rig->rig_time_s();
    outcome.rig_steps = rig->steps_run();
  }
  outcome.plan = watch.plan();
  outcome.phasors = watch.analysis().phasors();
  return outcome;
}

}  // namespace beamid::workflow
