// A stepped-sine rig on the time-domain simulator that runs one step at a
// time on request, as a test guided while it runs asks for them: each step
// drives the scenario's level (by its label) at the frequency asked for,
// settles exactly settle_s and records record_s (after the scenario's
// transient_s, which the recording keeps), carrying the beam's state from
// step to step as a real sweep does (hb/stepped_sine.h Step); a change of
// level keeps the beam moving (the shaker's amplitude changes, it does not
// stop). Every step is written at once as a campaign does
// (hb/campaign_writer.h, live): its recording, then campaign.json listing
// it; truth.json when the test is finished.
#pragma once

#include <filesystem>
#include <memory>
#include <string>

#include "hb/campaign_writer.h"
#include "hb/scenario.h"
#include "hb/stepped_sine.h"

namespace beamid::hb {

class VirtualRig {
 public:
  // Throws std::invalid_argument for an inconsistent scenario or a folder
  // that holds a campaign already.
  VirtualRig(const Scenario& scenario, const std::filesystem::path& folder);
  ~VirtualRig();

  // Runs and writes one step. Throws std::invalid_argument for a level the
  // scenario does not have, a frequency ≤ 0, settle_s < transient_s or
  // record_s ≤ 0.
  const SimulatedStep& Run(const std::string& level, double frequency_hz, double settle_s, double record_s);
  // Writes truth.json (and campaign.json once more).
  void Finish();

  // Rig time so far: every step's settle plus record [s].
  double rig_time_s() const { return rig_time_s_; }
  int steps_run() const { return steps_run_; }
  const SteppedSineSimulation& simulation() const { return *simulation_; }

 private:
  std::unique_ptr<SteppedSineSimulation> simulation_;
  std::unique_ptr<CampaignWriter> writer_;
  SimulatedStep last_;
  double rig_time_s_ = 0.0;
  int steps_run_ = 0;
};

}  // namespace beamid::hb
