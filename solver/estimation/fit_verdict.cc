#include "solver/estimation/fit_verdict.h"

#include <fmt/core.h>

namespace beamid::solver {

FitVerdict JudgeFit(double reduced_chi_square) {
  if (reduced_chi_square <= kMisfitReducedChiSquare)
    return {.within_noise = true,
            .text = fmt::format("fits within the noise (reduced chi-square {:.3g}, at most {:g} allowed)",
                                reduced_chi_square, kMisfitReducedChiSquare)};
  return {.within_noise = false,
          .text = fmt::format("misfits beyond the noise (reduced chi-square {:.3g}, at most {:g} allowed): the model "
                              "lacks some physics or the recordings hold a fault; run 'beamid diagnose'",
                              reduced_chi_square, kMisfitReducedChiSquare)};
}

}  // namespace beamid::solver
