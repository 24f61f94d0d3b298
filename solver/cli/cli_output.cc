#include "solver/cli/cli_output.h"

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <stdexcept>

#include <fmt/core.h>
#include <unistd.h>

#include "signal/campaign_extractor.h"
#include "signal/phasor_set_io.h"

namespace beamid::cli {

Progress::Progress(std::string label, bool quiet)
    : label_(std::move(label)), quiet_(quiet), terminal_(isatty(fileno(stderr)) != 0) {}

Progress::~Progress() { Done(); }

void Progress::Update(double fraction) {
  if (quiet_ || done_) return;
  const int percent = static_cast<int>(100.0 * std::clamp(fraction, 0.0, 1.0));
  if (terminal_ ? percent == last_percent_ : percent / 10 == last_percent_ / 10) return;
  last_percent_ = percent;
  if (terminal_)
    fmt::print(stderr, "\r{}  {:3d} %", label_, percent);
  else
    fmt::print(stderr, "{}  {:3d} %\n", label_, percent);
  std::fflush(stderr);
}

void Progress::Done() {
  if (quiet_ || done_) return;
  done_ = true;
  if (terminal_) fmt::print(stderr, "\r{}  done \n", label_);
}

nlohmann::json PhasorsToJson(const Eigen::VectorXcd& phasors) {
  nlohmann::json out = nlohmann::json::array();
  for (const auto& p : phasors) out.push_back({p.real(), p.imag()});
  return out;
}

void WriteTextFile(const std::filesystem::path& path, const std::string& text) {
  std::error_code error;
  if (path.has_parent_path()) std::filesystem::create_directories(path.parent_path(), error);
  std::ofstream out(path);
  if (!out) throw std::invalid_argument(path.string() + ": cannot write this file (check the folder and permissions)");
  out << text;
  if (!out) throw std::invalid_argument(path.string() + ": writing failed (disk full?)");
}

signal::PhasorSet ReadOrExtractPhasors(const signal::Campaign& campaign, const std::string& phasors_file,
                                       int num_harmonics, bool quiet) {
  if (!phasors_file.empty()) return signal::ReadPhasorSetJson(phasors_file);
  Progress progress("extract", quiet);
  signal::ExtractOptions extract;
  extract.estimator.num_harmonics = num_harmonics;
  extract.progress = [&](std::size_t done, std::size_t total, const signal::StepPhasors&) {
    progress.Update(static_cast<double>(done) / total);
  };
  return signal::ExtractCampaign(campaign, extract);
}

}  // namespace beamid::cli
