#include "solver/backbone/sweep_jumps.h"

#include <cmath>
#include <numbers>
#include <optional>

#include "hb/option_checks.h"

namespace beamid::solver {

void SweepJumpOptions::Validate() const {
  using namespace option_checks;
  RequirePositive("SweepJumpOptions.slope_factor", slope_factor);
  RequirePositive("SweepJumpOptions.noise_sigmas", noise_sigmas);
}

namespace {

double OmegaSquared(const SweepPoint& p) { return std::pow(2 * std::numbers::pi * p.frequency_hz, 2); }

// How far the change of G from step i to j misses the straight line (in ω²)
// through steps k0, k1 (the two steps before i, or the two after j), relative
// to the change that line predicts; nullopt when those steps do not exist or
// were not taken in the same sweep direction.
struct Miss {
  double relative = 0.0;  // |miss| / |predicted change|
  double absolute = 0.0;  // |miss| [N/m]
  // The miss over the branch's slope dG/dω² (= −1/A for one mode): a change
  // of branch moves ω_n² (real) far more than ζω_n (imaginary), so a fold's
  // miss lies along the slope; noise's points anywhere.
  bool along_the_branch = false;
};

std::optional<Miss> OneSidedMiss(const std::vector<SweepPoint>& points, int i, int j, int k0, int k1) {
  const int n = static_cast<int>(points.size());
  if (k0 < 0 || k1 < 0 || k0 >= n || k1 >= n) return std::nullopt;
  const double dx_pair = OmegaSquared(points[j]) - OmegaSquared(points[i]);
  const double dx_side = OmegaSquared(points[k1]) - OmegaSquared(points[k0]);
  if (dx_side == 0.0 || (dx_side > 0) != (dx_pair > 0)) return std::nullopt;
  const std::complex<double> slope =
      (points[k1].inverse_receptance_N_m - points[k0].inverse_receptance_N_m) / dx_side;
  const std::complex<double> predicted = slope * dx_pair;
  const std::complex<double> actual = points[j].inverse_receptance_N_m - points[i].inverse_receptance_N_m;
  const double miss = std::abs(actual - predicted);
  const std::complex<double> along = (actual - predicted) / slope;
  return Miss{.relative = miss / std::abs(predicted),
              .absolute = miss,
              .along_the_branch = std::abs(along.imag()) <= std::abs(along.real())};
}

}  // namespace

std::vector<SweepJump> DetectSweepJumps(const std::vector<SweepPoint>& points, const SweepJumpOptions& options) {
  options.Validate();
  const int n = static_cast<int>(points.size());
  // Per pair (i, i+1): the smaller of the two one-sided misses relative to
  // their predicted change, or 0 when the pair is no candidate.
  std::vector<double> score(n > 0 ? n - 1 : 0, 0.0);
  for (int i = 0; i + 1 < n; ++i) {
    const int j = i + 1;
    if (points[i].frequency_hz == points[j].frequency_hz) continue;
    const auto before = OneSidedMiss(points, i, j, i - 1, i);
    const auto after = OneSidedMiss(points, i, j, j, j + 1);
    if (!before && !after) continue;
    double relative = INFINITY, absolute = INFINITY;
    bool like_a_fold = true;
    for (const auto& side : {before, after})
      if (side) {
        relative = std::min(relative, side->relative), absolute = std::min(absolute, side->absolute);
        like_a_fold = like_a_fold && side->along_the_branch;
      }
    if (!like_a_fold) continue;
    // The noise of the change and of the extrapolations (the four steps, independent).
    double noise_sq = 0.0;
    for (int k = std::max(0, i - 1); k <= std::min(n - 1, j + 1); ++k)
      noise_sq += std::pow(points[k].inverse_receptance_std_N_m, 2);
    if (relative > options.slope_factor && absolute > options.noise_sigmas * std::sqrt(noise_sq)) score[i] = relative;
  }
  std::vector<SweepJump> jumps;
  for (int i = 0; i + 1 < n; ++i) {
    if (score[i] == 0.0) continue;
    // The last step before a fold bends too: of adjacent candidates, the largest miss.
    if ((i > 0 && score[i - 1] > score[i]) || (i + 2 < n && score[i + 1] >= score[i])) continue;
    const SweepPoint &a = points[i], &b = points[i + 1];
    const std::complex<double> ratio = a.inverse_receptance_N_m / b.inverse_receptance_N_m;  // (X/F)_b / (X/F)_a
    jumps.push_back({.from_step = i,
                     .to_step = i + 1,
                     .from_frequency_hz = a.frequency_hz,
                     .to_frequency_hz = b.frequency_hz,
                     .up_sweep = b.frequency_hz > a.frequency_hz,
                     .receptance_ratio = std::abs(ratio),
                     .phase_change_rad = std::arg(ratio),
                     .miss_over_predicted = score[i]});
  }
  return jumps;
}

}  // namespace beamid::solver
