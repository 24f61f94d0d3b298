#include "signal/first_harmonic_level.h"

#include "signal/input_error.h"

namespace beamid::signal {

std::vector<FirstHarmonicLevel> FirstHarmonicLevels(const PhasorSet& set, std::string_view channel,
                                                    const std::string& source) {
  std::vector<FirstHarmonicLevel> levels;
  for (const StepPhasors& step : set.steps) {
    const ChannelPhasors* response = step.Find(channel);
    if (response == nullptr || response == &step.force) {
      std::string known;
      for (const auto& r : step.responses) known += (known.empty() ? "" : ", ") + r.channel;
      throw InputError(source, std::string(channel), "no such response channel in step '" + step.file + "'",
                       "choose one of: " + known);
    }
    FirstHarmonicLevel* level = nullptr;
    for (auto& l : levels)
      if (l.label == step.level) level = &l;
    if (level == nullptr) {
      levels.push_back({.label = step.level,
                        .source = source,
                        .channel = response->channel,
                        .response_quantity = response->quantity,
                        .response_position_m = response->position_m});
      level = &levels.back();
    }
    level->points.push_back({.frequency_hz = step.frequency_hz,
                             .frequency_std_hz = step.frequency_std_hz,
                             .force = step.force.Harmonic(1),
                             .response = response->Harmonic(1)});
  }
  return levels;
}

}  // namespace beamid::signal
