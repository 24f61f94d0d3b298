// How a ring-down (signal/free_decay.h) is written in beamid's JSON files:
// the phasors file's steps and the measured backbone's levels declare it
// alike (hb/json_schema.h: one declaration writes, reads and documents).
// Amplitudes are in the channel's SI unit.
#pragma once

#include <cstddef>

#include "hb/json_schema.h"
#include "signal/free_decay.h"

namespace beamid::signal {

// Windows of a few periods over a ring-down that outlasts no record.
inline constexpr std::size_t kMaxDecayPoints = 100'000;

void Describe(auto& io, schema::Like<DecayPoint> auto& p) {
  constexpr std::string_view kUnit = "the channel's";
  io.Number("time_s", p.time_s, "s", schema::NonNegative());
  io.Number("amplitude", p.amplitude, kUnit, schema::NonNegative());
  io.Number("frequency_Hz", p.frequency_hz, "Hz", schema::Positive());
  io.Number("frequency_std_Hz", p.frequency_std_hz, "Hz", schema::NonNegative());
  io.Number("damping_ratio", p.damping_ratio, "1");
  io.Number("damping_ratio_std", p.damping_ratio_std, "1", schema::NonNegative());
  io.Number("residual_rms", p.residual_rms, kUnit, schema::NonNegative());
}

void Describe(auto& io, schema::Like<FreeDecay> auto& d) {
  io.Text("channel", d.channel, schema::TextRule::kNotEmpty);
  io.Number("start_s", d.start_s, "s", schema::NonNegative());
  io.List("points", d.points, kMaxDecayPoints);
}

}  // namespace beamid::signal
