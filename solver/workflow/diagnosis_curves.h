// The response curves of a diagnosis (`diagnose --curves PREFIX`): per level
// and channel the measured first-harmonic amplitude, the base model's and the
// diagnosed model's, as PREFIX.csv, a gnuplot script PREFIX.gp and its
// picture PREFIX.png.
#pragma once

#include <string>

#include "solver/diagnosis/diagnosis.h"

namespace beamid::workflow {

// A gnuplot script, one panel per channel: per level the measured
// first-harmonic amplitude (points), the base model (dashed) and the
// diagnosed model (solid) against frequency. The numbers go in as one
// datablock per level and channel; labels and names only as quoted texts
// (GnuplotText), so none can become a gnuplot command. The PNG goes to
// standard output: the script names no file.
std::string DiagnosisCurvesScript(const solver::DiagnosisResult& result);

// Writes PREFIX.csv and PREFIX.gp and draws PREFIX.png with gnuplot (run
// without a shell). A missing or failing gnuplot leaves the CSV and the
// script: the returned text says why the picture is missing (empty: drawn).
std::string WriteDiagnosisCurves(const solver::DiagnosisResult& result, const std::string& prefix);

}  // namespace beamid::workflow
