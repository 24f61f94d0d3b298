// Test support: the diagnosis the proofs and benchmarks run on a campaign's
// phasors. acc1 and acc2 are fitted (harmonics 1..3), acc3 is held out and
// the fitted channels are located up to the 5th harmonic, on 2 workers.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "signal/campaign.h"
#include "signal/phasor_set.h"
#include "solver/diagnosis/diagnosis.h"
#include "solver/estimation/fit_data.h"

namespace beamid::testing {

struct ProofData {
  solver::FitData fit;         // acc1, acc2, harmonics 1..3
  solver::FitData validation;  // acc3
  solver::FitData located;     // acc1, acc2, harmonics 1..5
};

// `options`' channels and harmonics are set here; the rest (the weighting) is kept.
inline ProofData MakeProofData(const signal::Campaign& campaign, const signal::PhasorSet& phasors,
                               solver::FitDataOptions options = {}) {
  auto data = [&](std::vector<std::string> channels, int harmonics) {
    options.channels = std::move(channels);
    options.num_fit_harmonics = harmonics;
    return solver::MakeFitData(campaign, phasors, options);
  };
  return {.fit = data({"acc1", "acc2"}, 3), .validation = data({"acc3"}, 3), .located = data({"acc1", "acc2"}, 5)};
}

inline solver::DiagnosisResult DiagnoseProofData(const ProofData& data, solver::DiagnosisOptions options = {}) {
  options.num_workers = 2;
  return solver::Diagnose(data.fit, data.validation, data.located, options);
}

}  // namespace beamid::testing
