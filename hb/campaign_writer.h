// Writes a simulated stepped-sine test to disk: the campaign exactly as
// docs/campaign-format.md defines it (campaign.json, by its one declaration
// hb/campaign_file.h, with the
// NOMINAL beam, one CSV per step with time_s and every channel in its written
// unit, noise added by hb/noise.h) and, beside it, truth.json: the true
// physics and the noise-free harmonic phasors of every step
// (docs/simulator.md describes its fields).
#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "hb/campaign_file.h"
#include "hb/noise.h"
#include "hb/scenario.h"
#include "hb/stepped_sine.h"

namespace beamid::hb {

struct CampaignWriterOptions {
  // Replace an existing campaign.json in the directory (otherwise an error).
  bool overwrite = false;
  // Rewrite campaign.json after every step, listing the steps written so
  // far, as an acquisition does while the test runs (a virtual rig that a
  // live analysis follows); else it is written once, last, by Finish.
  bool live = false;
};

class CampaignWriter {
 public:
  // Creates the directory. Throws std::invalid_argument if it holds a
  // campaign already (unless overwrite) or cannot be created.
  CampaignWriter(const SteppedSineSimulation& simulation, const std::filesystem::path& directory,
                 const CampaignWriterOptions& options = {});
  ~CampaignWriter();

  // Adds noise, writes the step's CSV and keeps its truth. Steps arrive in
  // run order. Throws std::runtime_error on an I/O failure.
  void Write(const SimulatedStep& step);
  // Writes campaign.json and truth.json.
  void Finish();
  // campaign.json's content for the steps written so far.
  CampaignFile CampaignSoFar() const;

  std::uintmax_t bytes_written() const { return bytes_written_; }
  int clipped_samples() const { return clipped_samples_; }

 private:
  const SteppedSineSimulation& simulation_;
  std::filesystem::path directory_;
  bool live_ = false;
  MeasurementNoise noise_;
  std::vector<CampaignStep> campaign_steps_;
  std::unique_ptr<nlohmann::json> truth_steps_;
  std::unique_ptr<nlohmann::json> early_records_;  // truth.json's measurement_artefacts.early_records
  std::uintmax_t bytes_written_ = 0;
  int clipped_samples_ = 0;
};

}  // namespace beamid::hb
