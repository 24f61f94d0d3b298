// The watch use case: a campaign folder followed while the acquisition
// writes it (signal/campaign_follower.h), each completed step analysed at
// once (solver/live/live_analysis.h: extracted, judged, the identification
// refitted from its optimum, the next step planned) and the plan written
// atomically to plan_file after every step (solver/live/test_plan_io.h),
// where the DAQ script reads what to measure next. With a virtual rig (a
// scenario of the time-domain simulator, hb/virtual_rig.h) the loop is
// closed in one process: the rig runs each planned step and writes it into
// the folder, which the watch then reads like any other acquisition's.
#pragma once

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "signal/campaign_follower.h"
#include "signal/phasor_set.h"
#include "solver/live/live_analysis.h"
#include "solver/live/test_plan.h"
#include "solver/workflow/run_observer.h"

namespace beamid::workflow {

struct WatchRequest {
  std::string campaign_folder;
  std::string plan_file = "plan.json";
  solver::LiveOptions live;
  signal::CampaignFollowerOptions follower;
  double poll_s = 0.25;           // between looks at the folder
  double idle_timeout_s = 600.0;  // stop when no step completes for this long (0: never)
  // A scenario file: run the time-domain simulator as the rig (closed loop).
  std::string virtual_rig;

  // Throws InputError naming the option and the fix: values out of range,
  // a plan file inside the campaign folder or that is no file.
  void Validate() const;
};

// Follows one folder; Poll is called by the loop below, or by a test with its
// own clock.
class CampaignWatch {
 public:
  // Validates the request and writes the first plan.
  explicit CampaignWatch(const WatchRequest& request);
  ~CampaignWatch();

  // Looks once at time now_s; each completed step is analysed and the plan
  // rewritten. Throws InputError for a campaign that cannot be followed.
  std::vector<solver::LiveUpdate> Poll(double now_s);
  const solver::TestPlan& plan() const { return analysis_.plan(); }
  const solver::LiveAnalysis& analysis() const { return analysis_; }

 private:
  WatchRequest request_;
  signal::CampaignFollower follower_;
  solver::LiveAnalysis analysis_;
};

struct WatchOutcome {
  solver::TestPlan plan;      // the last one written
  signal::PhasorSet phasors;  // the usable steps, level by level, each upwards
  int steps_handed_out = 0;   // by the follower, faulty ones included
  bool idle_timeout = false;  // stopped because nothing came
  double rig_time_s = 0.0;    // virtual rig: its settle + record time
  int rig_steps = 0;          // virtual rig: steps it ran
};

using LiveUpdateCallback = std::function<void(const solver::LiveUpdate& update)>;

// Follows the folder until the plan is done (or the idle timeout), calling
// on_update after every step. With request.virtual_rig the rig runs each
// planned step first (the loop's clock is then virtual: no waiting).
WatchOutcome WatchCampaign(const WatchRequest& request, const RunObserver& observer = {},
                           const LiveUpdateCallback& on_update = {});

}  // namespace beamid::workflow
