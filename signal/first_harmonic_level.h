// One level of a stepped-sine test reduced to its first harmonic: per step the
// excitation frequency, the force phasor F and one response phasor X (peak,
// SI, with the 2×2 covariance of Re/Im as in signal/phasor_set.h). This is
// what acquisition systems export ("frequency, force amplitude, response
// amplitude, phase") and what the model-free measured backbone
// (solver/measured_backbone.h) works on: X/F is the measured first-harmonic
// frequency response at that level.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "signal/phasor_set.h"
#include "signal/quantity.h"

namespace beamid::signal {

struct FirstHarmonicPoint {
  double frequency_hz = 0.0;
  double frequency_std_hz = 0.0;
  HarmonicPhasor force;     // F [N]
  HarmonicPhasor response;  // X in the level's response quantity [SI]
};

struct FirstHarmonicLevel {
  std::string label;    // the campaign's level label, or the table's file name
  std::string source;   // the file it came from, for messages
  std::string channel;  // response channel name ("" when unknown)
  Quantity response_quantity = Quantity::kAcceleration;
  double response_position_m = -1.0;  // < 0: unknown (a table does not say)
  std::vector<FirstHarmonicPoint> points;  // in run order
};

// The levels of a campaign's phasors (levels in order of first appearance,
// steps in run order) for one response channel. Throws InputError naming the
// phasor file `source` when the channel does not exist.
std::vector<FirstHarmonicLevel> FirstHarmonicLevels(const PhasorSet& set, std::string_view channel,
                                                    const std::string& source);

}  // namespace beamid::signal
