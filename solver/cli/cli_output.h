// Shared by the subcommands: progress on stderr, CSV/JSON writing with clear
// errors, and the conversion of displacement phasors to the other quantities.
#pragma once

#include <complex>
#include <filesystem>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include "signal/campaign.h"
#include "signal/phasor_set.h"

namespace beamid::cli {

// A one-line progress indicator on stderr ("label  42 %"), silent when quiet
// or when stderr is not a terminal (then one line per 10 %).
class Progress {
 public:
  Progress(std::string label, bool quiet);
  ~Progress();
  void Update(double fraction);
  void Done();

 private:
  std::string label_;
  bool quiet_;
  bool terminal_;
  int last_percent_ = -1;
  bool done_ = false;
};

// [re, im] pairs, the JSON form of a complex phasor everywhere in beamid.
nlohmann::json PhasorsToJson(const Eigen::VectorXcd& phasors);

// Writes text to a file, creating its folder; throws std::invalid_argument
// naming the path if it cannot.
void WriteTextFile(const std::filesystem::path& path, const std::string& text);

// The phasors of a campaign: read from `phasors_file` (the output of
// `beamid extract`) when given, else extracted with harmonics 1..num_harmonics
// and progress on stderr.
signal::PhasorSet ReadOrExtractPhasors(const signal::Campaign& campaign, const std::string& phasors_file,
                                       int num_harmonics, bool quiet);

}  // namespace beamid::cli
