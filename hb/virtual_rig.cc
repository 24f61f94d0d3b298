#include "hb/virtual_rig.h"

#include <stdexcept>

namespace beamid::hb {

VirtualRig::VirtualRig(const Scenario& scenario, const std::filesystem::path& folder) {
  Scenario rig = scenario;
  rig.timing.restart_each_level = false;
  simulation_ = std::make_unique<SteppedSineSimulation>(rig);
  writer_ = std::make_unique<CampaignWriter>(*simulation_, folder, CampaignWriterOptions{.live = true});
}

VirtualRig::~VirtualRig() = default;

const SimulatedStep& VirtualRig::Run(const std::string& level, double frequency_hz, double settle_s, double record_s) {
  const Scenario& scenario = simulation_->scenario();
  const ScenarioLevel* found = nullptr;
  for (const ScenarioLevel& candidate : scenario.levels)
    if (candidate.label == level) found = &candidate;
  if (!found)
    throw std::invalid_argument("the rig has no level \"" + level + "\": ask for one of the scenario's levels");
  if (!(frequency_hz > 0.0)) throw std::invalid_argument("a step's frequency must be positive");
  if (!(record_s > 0.0)) throw std::invalid_argument("a step's record_s must be positive");
  ScenarioTiming timing = scenario.timing;
  if (!(settle_s >= timing.transient_s))
    throw std::invalid_argument(
        "a step's settle_s must be at least the scenario's transient_s (the recording keeps it)");
  timing.settle_min_s = settle_s;
  timing.settle_max_s = settle_s;
  timing.record_s = record_s;
  last_ = simulation_->Step(*found, frequency_hz, timing);
  writer_->Write(last_);
  rig_time_s_ += last_.settle_s + record_s;
  ++steps_run_;
  return last_;
}

void VirtualRig::Finish() { writer_->Finish(); }

}  // namespace beamid::hb
