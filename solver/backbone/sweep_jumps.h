// Jumps of a stepped-sine sweep: the response leaving one branch of a folded
// (nonlinear) frequency response for another between two consecutive steps
// of the campaign, in either sweep direction and whatever the amplitude ratio.
//
// Why in the inverse receptance G = F/X_d, in run order: for one mode,
// A·G = ω_n²(a) − ω² + 2iω·ζω_n(a), so along a branch (a changing smoothly)
// G moves nearly linearly in ω², with a slope (−1/A) that never vanishes and
// does not depend on how coarse the steps are (|X_d/F| itself turns sharply
// at a resonance, so its steps cannot tell a jump from a coarse sweep). A
// jump changes a, hence ω_n²(a), between two steps: G moves by far more than
// the neighbouring steps' slope predicts. A pair of consecutive steps is a
// jump when the change of G between them misses both one-sided
// extrapolations (from the two steps before it and from the two after it,
// along the same sweep direction) by more than `slope_factor` times the
// change that extrapolation predicts and by more than `noise_sigmas` times
// the noise of the four steps, and misses them as a fold does: along the
// branch's slope dG/dω² = −1/A (a change of branch changes ω_n²(a), which
// is real, far more than ζω_n(a): |Im(miss/slope)| ≤ |Re(miss/slope)|),
// not in the random direction of noise; of adjacent candidates only the
// largest miss counts (the last step before a fold bends too). A table that
// states no noise gets one from its own scatter (measured_backbone.h).
// Why 2: a jump misses the extrapolation along the branch it lands on by
// about (its change of ω_n²)/(the step's Δω²), the backbone's shift between
// the branches in steps. On single-mode Duffing sweeps with steps of 0.05 to
// 0.5 Hz (ζ = 1 %), levels below the critical force (no fold) miss by at most
// 1.6, jumps by 1.7 to 100 (a small jump's down-sweep least), and a level
// whose bistable band is narrower than a step (the fold falls between two
// steps: the sweep jumps there) by up to 2.6; the paper set-up's 9 N
// up-sweep jumps with a miss of 2.3, which the former threshold of 3 let by.
#pragma once

#include <complex>
#include <vector>

namespace beamid::solver {

struct SweepPoint {
  double frequency_hz = 0.0;
  std::complex<double> inverse_receptance_N_m;  // G = F/X_d
  double inverse_receptance_std_N_m = 0.0;      // √(var Re G + var Im G); 0 = no noise given
};

struct SweepJump {
  int from_step = 0, to_step = 0;  // indices in run order (to_step = from_step + 1)
  double from_frequency_hz = 0.0, to_frequency_hz = 0.0;
  bool up_sweep = true;               // the frequency rose between the two steps
  double receptance_ratio = 1.0;      // |X_d/F| after / before (< 1: a drop)
  double phase_change_rad = 0.0;      // arg of (X_d/F after)/(X_d/F before), in (−π, π]
  double miss_over_predicted = 0.0;   // the smaller one-sided miss / the change it predicted
};

struct SweepJumpOptions {
  double slope_factor = 2.0;
  double noise_sigmas = 5.0;
  // Throws InputError naming the field, its value and the allowed range.
  void Validate() const;
};

// `points` in run order. Pairs at the same frequency are skipped.
std::vector<SweepJump> DetectSweepJumps(const std::vector<SweepPoint>& points, const SweepJumpOptions& options = {});

}  // namespace beamid::solver
