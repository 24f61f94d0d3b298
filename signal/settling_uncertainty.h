// A record cut before its transient decayed (a step recorded too early, most
// often the first one after a jump, where the transient near a fold decays
// slowly): whatever steady part the detection keeps still holds the rest of
// the transient, and the phasors of that part are off by it. The noise-based
// covariance does not see that error; the change between the two halves of
// the analysed part does:
//     ΔX_k = X_k(first half) − X_k(second half)   (both referenced to F_1)
// is ~ the transient left, where a settled record changes only by noise
// (Cov ΔX ≈ 4·Cov X). Where |ΔX_k|² exceeds that noise by more than
// significance_chi2 (χ² with 2 dof), the phasor's covariance gets
// |ΔX_k|²/2 per component: its expected squared error then equals the change
// seen, so a fit weighs the step by what it is worth instead of being pulled
// by it.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "signal/campaign.h"
#include "signal/phasor_set.h"

namespace beamid::signal {

struct SettlingUncertainty {
  bool raised = false;  // some phasor's covariance was raised
  // The largest |ΔX_1|/|X_1| of a channel whose uncertainty was raised, and
  // that channel; 0 and empty when no change exceeded the noise.
  double change_relative = 0.0;
  std::string channel;
};

// samples: the analysed (steady) part, columns in specs order, the reference
// (force) first; phasors: the same part's, as ReferencePhasors packed them.
// Raises the covariances of `phasors` in place, for the channels whose
// `used` flag is set.
SettlingUncertainty AddSettlingUncertainty(const Eigen::Ref<const Eigen::MatrixXd>& samples, double sample_rate_hz,
                                           double frequency_hz, int num_harmonics,
                                           const std::vector<const ChannelSpec*>& specs,
                                           const std::vector<bool>& used, std::vector<ChannelPhasors>& phasors,
                                           double significance_chi2 = 13.8);

}  // namespace beamid::signal
