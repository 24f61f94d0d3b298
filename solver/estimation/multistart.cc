#include "solver/estimation/multistart.h"

#include <algorithm>
#include <cmath>

namespace beamid::solver {

MinimaSummary SummarizeMinima(const std::vector<StartOutcome>& starts, const std::vector<ParameterBounds>& bounds,
                              int degrees_of_freedom, double decisive_gap) {
  std::vector<const StartOutcome*> converged;
  for (const auto& s : starts)
    if (s.success) converged.push_back(&s);
  std::stable_sort(converged.begin(), converged.end(),
                   [](const StartOutcome* a, const StartOutcome* b) { return a->objective < b->objective; });
  MinimaSummary summary;
  for (const StartOutcome* s : converged) {
    const double chi_square = 2.0 * s->objective;
    const auto same = [&](const LocalMinimum& m) {
      if (std::abs(chi_square - m.chi_square) > 1e-4 * m.chi_square + 1e-9) return false;
      for (std::size_t j = 0; j < m.parameters.size(); ++j) {
        const double scale = std::max(std::abs(m.parameters[j]), j < bounds.size() ? bounds[j].typical : 0.0);
        if (std::abs(s->parameters[j] - m.parameters[j]) > 1e-3 * scale) return false;
      }
      return true;
    };
    const auto found = std::find_if(summary.minima.begin(), summary.minima.end(), same);
    if (found == summary.minima.end())
      summary.minima.push_back({.parameters = s->parameters, .chi_square = chi_square, .num_starts = 1});
    else
      ++found->num_starts;
  }
  if (summary.minima.size() > 1) {
    const double best = summary.minima[0].chi_square;
    const double scatter = std::max(1.0, best / std::max(1, degrees_of_freedom));
    summary.second_chi_square_gap = (summary.minima[1].chi_square - best) / scatter;
    summary.decisive = summary.second_chi_square_gap >= decisive_gap;
  }
  return summary;
}

}  // namespace beamid::solver
