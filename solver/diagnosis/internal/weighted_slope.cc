#include "solver/diagnosis/internal/weighted_slope.h"

#include <algorithm>
#include <cmath>

namespace beamid::solver::internal {

std::pair<double, double> WeightedSlope(const std::vector<double>& x, const std::vector<double>& y,
                                        const std::vector<double>& sigma) {
  const int n = static_cast<int>(x.size());
  double sw = 0, sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (int i = 0; i < n; ++i) {
    const double w = 1.0 / (sigma[i] * sigma[i]);
    sw += w, sx += w * x[i], sy += w * y[i], sxx += w * x[i] * x[i], sxy += w * x[i] * y[i];
  }
  const double det = sw * sxx - sx * sx;
  if (n < 2 || !(det > 0.0)) return {std::nan(""), std::nan("")};
  const double b = (sw * sxy - sx * sy) / det, a = (sy - b * sx) / sw;
  if (n < 3) return {b, std::nan("")};
  double chi2 = 0.0;
  for (int i = 0; i < n; ++i) chi2 += std::pow((y[i] - a - b * x[i]) / sigma[i], 2);
  return {b, std::sqrt(sw / det) * std::max(1.0, std::sqrt(chi2 / (n - 2)))};
}

}  // namespace beamid::solver::internal
