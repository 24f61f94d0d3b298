// Weighted least-squares straight line y = a + b·x, for the exponents of
// the misfit location (log–log slopes over levels and steps).
#pragma once

#include <utility>
#include <vector>

namespace beamid::solver::internal {

// Returns b and its σ; the σ is scaled by sqrt(χ²/(n−2)) when the scatter
// exceeds the stated σ. b is NaN with fewer than 2 points (or all x equal),
// its σ NaN with fewer than 3.
std::pair<double, double> WeightedSlope(const std::vector<double>& x, const std::vector<double>& y,
                                        const std::vector<double>& sigma);

}  // namespace beamid::solver::internal
