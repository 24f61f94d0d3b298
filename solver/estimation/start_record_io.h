// One start of Identify as a worker process hands it back: its outcome
// (multistart.h's StartOutcome) and the optimiser's variables at its end
// point, as text with every double exact (non-finite ones included), so that
// an identification is the same with any number of worker processes. The
// diagnosis's refits travel the same way (diagnosis_io.h, CandidateRefit).
#pragma once

#include <string>
#include <vector>

#include "solver/estimation/multistart.h"

namespace beamid::solver {

struct StartRecord {
  StartOutcome outcome;   // its start is the parent's to fill
  std::vector<double> x;  // the optimiser's variables at the end point
};

std::string StartRecordToText(const StartRecord& record);
// Throws std::runtime_error on text StartRecordToText did not write.
StartRecord StartRecordFromText(const std::string& text);

}  // namespace beamid::solver
