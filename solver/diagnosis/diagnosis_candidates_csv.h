// The diagnosis' candidate table as a CSV a spreadsheet opens (`beamid
// diagnose --csv FILE`, docs/diagnose.md): the base model, then one row per
// candidate physics in the diagnosis' ranking, then the pairs tried after
// the named cause. Each row: its rank; the verdict on the rows it names
// ("cause named", "causes indistinguishable", "combination named"; empty
// otherwise); the signature score against the located misfit; the refit
// status; whether it is a fault of the recording; χ², degrees of freedom,
// reduced χ², AIC, BIC; the likelihood ratio Λ against the base (against
// the cause alone for a pair) with its q and p, significance and
// χ²_base/χ²; the held-out χ² and first-harmonic error; the candidate's own
// parameters ("name = value ± σ unit; ..."); why it was not refitted; what
// to check on the rig. Cells not computed are empty (hb/csv_cell.h).
#pragma once

#include <string>

#include "solver/diagnosis/diagnosis.h"

namespace beamid::solver {

std::string DiagnosisCandidatesCsv(const DiagnosisResult& diagnosis);

}  // namespace beamid::solver
