// One level of a stepped-sine test reduced to its first harmonic: per step the
// excitation frequency, the force phasor F and one response phasor X (peak,
// SI, with the 2×2 covariance of Re/Im as in signal/phasor_set.h). This is
// what acquisition systems export ("frequency, force amplitude, response
// amplitude, phase") and what the model-free measured backbone
// (solver/measured_backbone.h) works on: X/F is the measured first-harmonic
// frequency response at that level.
//
// The excitation need not be a force: with a drive voltage X/F is the
// response per volt, with a base acceleration the response is taken
// relative to the base (X − A_b for an accelerometer: the absolute
// acceleration holds the base's own motion, which is no part of the mode),
// and F is −A_b, so that X/F is the relative response per base
// acceleration with the form and sign of a single mode's receptance under
// the inertial load −m·a_b.
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
  HarmonicPhasor force;     // F [N], or the drive voltage [V], or −A_b [m/s²] (base excitation)
  HarmonicPhasor response;  // X in the level's response quantity [SI]
  // The response's ring-down after the step's excitation stopped
  // (signal/free_decay.h); empty when it ran to the record's end.
  std::vector<DecayPoint> free_decay;
};

struct FirstHarmonicLevel {
  std::string label;    // the campaign's level label, or the table's file name
  std::string source;   // the file it came from, for messages
  std::string channel;  // response channel name ("" when unknown)
  Quantity response_quantity = Quantity::kAcceleration;
  Quantity excitation_quantity = Quantity::kForce;
  double response_position_m = -1.0;  // < 0: unknown (a table does not say)
  std::vector<FirstHarmonicPoint> points;  // in run order
};

// A base-excited step as measured, the absolute response X and the base's
// acceleration A_b, made what a level holds: X − A_b and −A_b (see above).
// The two channels' noises are independent: their covariances add.
void ReferToBase(HarmonicPhasor& response, HarmonicPhasor& base_acceleration);

// The levels of a campaign's phasors (levels in order of first appearance,
// steps in run order) for one response channel. Throws InputError naming the
// phasor file `source` when the channel does not exist, or when a base
// excitation's response is not an acceleration (its relative motion would
// need the base's integrated motion).
std::vector<FirstHarmonicLevel> FirstHarmonicLevels(const PhasorSet& set, std::string_view channel,
                                                    const std::string& source);

}  // namespace beamid::signal
