// One level of a stepped-sine test from a universal file, as frequency-domain
// systems export a stepped sine's result (LMS Test.Lab / Simcenter, m+p,
// pyuff): datasets 58 of complex ordinates over the steps' frequencies
// (signal/uff58.h, Uff58Functions::kFrequencyFunctions). The file holds the
// force's spectrum (function type 12, the force: record 9's specific data
// type 13 or 9, or the unit N) and the response as either its spectrum
// (function type 12) or its frequency response function to the force
// (function type 4, record 9 the response's unit, record 10 the force's):
// then X = H·F at each step. A frequency response alone is refused: a
// nonlinear level needs the force amplitude it was measured at. Datasets of
// other function types (time histories) are ignored.
//
// The steps are the points in the file's order (the run order, for the
// jumps); the abscissa is the frequency in Hz (record 8: empty, Hz; data
// type 18 or 0/1). Every phasor is turned so that the force is real and
// positive (beamid's reference, signal/phasor_set.h). The response quantity
// comes from record 9's specific data type (8 displacement, 11 velocity, 12
// acceleration) or its unit, values to SI by that unit (signal/quantity.h).
// No uncertainty is stated: the measured backbone estimates the noise from
// the sweep. Anything wrong throws InputError naming the file, the dataset
// and the fix.
#pragma once

#include <string>
#include <vector>

#include "signal/first_harmonic_level.h"
#include "signal/uff58.h"

namespace beamid::signal {

FirstHarmonicLevel FirstHarmonicLevelFromUff58(const std::vector<Uff58Dataset>& datasets, const std::string& source,
                                               const std::string& label);

// Reads the file (the level's label is its name without the extension).
FirstHarmonicLevel ReadUff58Level(const std::filesystem::path& file);

}  // namespace beamid::signal
