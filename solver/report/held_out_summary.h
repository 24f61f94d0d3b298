// The words for a held-out channel's prediction error, as `beamid identify`
// prints them and the report shows them: the worst relative error on the
// 1st and 3rd harmonics over the steps that resolve it, with their count;
// a harmonic no step resolves is said to have nothing measurable, never
// "0.00 %" (which would read as a perfect prediction).
#pragma once

#include <string>

#include "solver/estimation/result_file.h"

namespace beamid::solver {

// E.g. "worst error 1.23 % on the 1st harmonic (over the 5 of 6 steps that
// resolve it); nothing measurable on the 3rd harmonic (none of the 6 steps
// resolves its error: all lie below the noise floor)".
std::string HeldOutSummary(const HeldOutChannel& channel);
// The same from its numbers (a report's record of them).
std::string HeldOutSummary(int steps, double worst_h1_relative_error, int measurable_steps_h1,
                           double worst_h3_relative_error, int measurable_steps_h3);

}  // namespace beamid::solver
