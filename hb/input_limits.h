// The sizes of the lists a user's file may give, checked when the file is
// read: beyond them the computations that follow would take minutes and
// gigabytes before any check could speak (8000 sensors in a model took 85 s
// and 6.8 GB), and no stepped-sine test comes near them.
#pragma once

namespace beamid::hb {

// Points of one beam in one list (sensors, point masses, hidden positions):
// a rig has a handful, and each point costs a node of the beam's mesh and a
// channel of every step.
inline constexpr int kMaxPointsOnBeam = 64;

}  // namespace beamid::hb
