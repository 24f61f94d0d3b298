#include "solver/report/diagnosis_residual_map.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace beamid::solver {

ResidualMap DiagnosisResidualMap(const std::vector<ResponsePoint>& response, DiagnosedModel model) {
  std::vector<std::string> channels;
  std::size_t harmonics = 0;
  std::vector<const ResponsePoint*> fitted;
  for (const auto& p : response) {
    if (p.held_out) continue;
    const auto& misfit = model == DiagnosedModel::kBase ? p.base_misfit_sigma : p.final_misfit_sigma;
    if (misfit.empty()) return {};
    harmonics = std::max(harmonics, misfit.size());
    if (std::find(channels.begin(), channels.end(), p.channel) == channels.end()) channels.push_back(p.channel);
    fitted.push_back(&p);
  }
  ResidualMap map;
  if (fitted.empty()) return map;
  for (const auto& c : channels)
    for (std::size_t k = 1; k <= harmonics; ++k) map.rows.push_back(c + " h" + std::to_string(k));
  // A new step where the level or the frequency changes (or a channel comes again).
  std::vector<int> column(fitted.size());
  std::vector<bool> seen(channels.size(), false);
  for (std::size_t j = 0; j < fitted.size(); ++j) {
    const ResponsePoint& p = *fitted[j];
    const auto c = static_cast<std::size_t>(std::find(channels.begin(), channels.end(), p.channel) - channels.begin());
    const bool same_step = j > 0 && p.level == fitted[j - 1]->level &&
                           p.frequency_hz == fitted[j - 1]->frequency_hz && !seen[c];
    if (!same_step) {
      std::fill(seen.begin(), seen.end(), false);
      map.step_level.push_back(p.level);
      map.step_frequency_hz.push_back(p.frequency_hz);
    }
    seen[c] = true;
    column[j] = static_cast<int>(map.step_level.size()) - 1;
  }
  map.whitened_norm = Eigen::MatrixXd::Constant(static_cast<Eigen::Index>(map.rows.size()),
                                                static_cast<Eigen::Index>(map.step_level.size()), std::nan(""));
  for (std::size_t j = 0; j < fitted.size(); ++j) {
    const ResponsePoint& p = *fitted[j];
    const auto c = static_cast<std::size_t>(std::find(channels.begin(), channels.end(), p.channel) - channels.begin());
    const auto& misfit = model == DiagnosedModel::kBase ? p.base_misfit_sigma : p.final_misfit_sigma;
    for (std::size_t k = 0; k < misfit.size(); ++k)
      map.whitened_norm(static_cast<Eigen::Index>(c * harmonics + k), column[j]) = misfit[k];
  }
  return map;
}

double SumOfSquares(const ResidualMap& map) {
  double sum = 0.0;
  for (Eigen::Index r = 0; r < map.whitened_norm.rows(); ++r)
    for (Eigen::Index i = 0; i < map.whitened_norm.cols(); ++i)
      if (std::isfinite(map.whitened_norm(r, i))) sum += map.whitened_norm(r, i) * map.whitened_norm(r, i);
  return sum;
}

}  // namespace beamid::solver
