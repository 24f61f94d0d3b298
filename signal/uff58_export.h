// One level of a stepped-sine test written as a universal file, the way a
// frequency-domain system exports a stepped sine's result, for a
// structural-dynamics tool (pyuff, ME'scope, Simcenter) to read
// (docs/uff58.md): dataset 151 (the file's origin), then two datasets 58 in
// ASCII, the excitation's spectrum (function type 12) and the response's
// frequency response to it (function type 4, H = X/F), complex double
// precision at uneven abscissae (record 7 spacing 0: each step's frequency
// in Hz before its value, in the run order), SI units in records 9 and 10
// with their specific data types (8/11/12 displacement, velocity,
// acceleration; 13 force; 0 for a voltage). Numbers are written E20.12, one
// step per line. signal/uff58_level.h reads a force-driven level back. A
// base-excited level is refused (InputError): it holds the motion relative
// to the base, not spectra.
#pragma once

#include <string>

#include "signal/first_harmonic_level.h"

namespace beamid::signal {

std::string Uff58LevelText(const FirstHarmonicLevel& level);

}  // namespace beamid::signal
