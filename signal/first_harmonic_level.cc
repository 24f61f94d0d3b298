#include "signal/first_harmonic_level.h"

#include <utility>

#include "signal/input_error.h"

namespace beamid::signal {

// Per −A_b: the load on the mode is −m·a_b, so X_rel/(−A_b) has a
// receptance's form and sign.
void ReferToBase(HarmonicPhasor& response, HarmonicPhasor& base_acceleration) {
  response.value -= base_acceleration.value;
  response.SetCovariance(response.Covariance() + base_acceleration.Covariance());
  base_acceleration.value = -base_acceleration.value;
}

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
    const bool base = step.force.quantity == Quantity::kBaseAcceleration;
    if (base && response->quantity != Quantity::kAcceleration)
      throw InputError(source, response->channel,
                       "with a base excitation the response must be an acceleration (its motion relative to the base "
                       "is the mode's)",
                       "choose an accelerometer's channel");
    if (level == nullptr) {
      levels.push_back({.label = step.level,
                        .source = source,
                        .channel = response->channel,
                        .response_quantity = response->quantity,
                        .excitation_quantity = step.force.quantity,
                        .response_position_m = response->position_m});
      level = &levels.back();
    }
    HarmonicPhasor x = response->Harmonic(1);
    HarmonicPhasor f = step.force.Harmonic(1);
    if (base) ReferToBase(x, f);
    std::vector<DecayPoint> free_decay;
    for (const FreeDecay& decay : step.free_decays)
      if (decay.channel == response->channel) free_decay = decay.points;
    level->points.push_back({.frequency_hz = step.frequency_hz,
                             .frequency_std_hz = step.frequency_std_hz,
                             .force = f,
                             .response = x,
                             .free_decay = std::move(free_decay)});
  }
  return levels;
}

}  // namespace beamid::signal
