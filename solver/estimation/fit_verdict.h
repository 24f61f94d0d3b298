// Whether a fit misses its data by more than their noise. The residuals are
// standardised by the phasors' stated uncertainties, so a model that holds
// the rig's physics gives χ²/ν ≈ 1 (below where the stated uncertainties are
// conservative). The limit is kMisfitReducedChiSquare = 2, not the χ²
// distribution's 1 + 3√(2/ν): the stated uncertainties are themselves
// estimated from each record's noise floor, to some 10–20 %, which alone
// moves χ²/ν by 20–40 %.
#pragma once

#include <string>

namespace beamid::solver {

inline constexpr double kMisfitReducedChiSquare = 2.0;

struct FitVerdict {
  bool within_noise = true;
  std::string text;  // "fits within the noise (...)" or "misfits beyond the noise (...): run 'beamid diagnose'"
};

FitVerdict JudgeFit(double reduced_chi_square);

}  // namespace beamid::solver
