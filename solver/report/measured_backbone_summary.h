// The command-line summary of `beamid backbone --measured`, as a person
// reads it: ONE line per level (its label, what controls it, the frequency
// at phase resonance ± σ, the displacement amplitude there, the level's ζ ± σ,
// the free decay's ζ after records that stop, and its flags as short words:
// [jump ×2] [coarse steps] [left out of the fit]), so that a noisy sweep that jumps hundreds of times still reads in
// one line; then the cross-level fit and the damping trend. Each jump's and
// flag's message and every note stay in PREFIX.json and on the page of
// `beamid report` (solver/report/measured_backbone_report.h). A number that
// could not be estimated is said in words with the reason, never "nan".
#pragma once

#include <string>
#include <vector>

#include "solver/backbone/measured_backbone.h"

namespace beamid::solver {

// One line per level, in the levels' order, without a line break.
std::vector<std::string> LevelSummaryLines(const MeasuredBackbone& measured);

// The cross-level single-mode fit and the damping trend, a line each.
std::vector<std::string> CrossLevelSummaryLines(const MeasuredBackbone& measured);

// A level's flags as short words, each kind once with its count, and
// whether it left the cross-level fit: "[jump ×2] [coarse steps]"; "" when
// none.
std::string FlagWords(const LevelResonance& level);

}  // namespace beamid::solver
