#include "signal/settling_uncertainty.h"

#include <algorithm>
#include <cmath>

#include <Eigen/LU>

#include "signal/harmonic_fit.h"
#include "signal/phasor_estimator.h"

namespace beamid::signal {

SettlingUncertainty AddSettlingUncertainty(const Eigen::Ref<const Eigen::MatrixXd>& samples, double sample_rate_hz,
                                           double frequency_hz, int num_harmonics,
                                           const std::vector<const ChannelSpec*>& specs,
                                           const std::vector<bool>& used, std::vector<ChannelPhasors>& phasors,
                                           double significance_chi2) {
  const Eigen::Index half = samples.rows() / 2;
  const auto first = ReferencePhasors(FitHarmonics(samples.topRows(half), sample_rate_hz, frequency_hz, num_harmonics), 0, specs);
  const auto second =
      ReferencePhasors(FitHarmonics(samples.bottomRows(half), sample_rate_hz, frequency_hz, num_harmonics), 0, specs);
  SettlingUncertainty result;
  for (std::size_t c = 0; c < phasors.size(); ++c) {
    if (!used[c]) continue;
    const std::size_t num_k = std::min({phasors[c].harmonics.size(), first[c].harmonics.size(), second[c].harmonics.size()});
    for (std::size_t k = 0; k < num_k; ++k) {
      HarmonicPhasor& phasor = phasors[c].harmonics[k];
      // The reference's fundamental is real by construction: its change is
      // the amplitude's alone, and its covariance has no imaginary part to test.
      if (c == 0 && k == 0) continue;
      const std::complex<double> change = first[c].harmonics[k].value - second[c].harmonics[k].value;
      const Eigen::Vector2d d(change.real(), change.imag());
      const Eigen::Matrix2d noise = 4.0 * phasor.Covariance();
      if (noise.determinant() <= 0.0 || d.dot(noise.inverse() * d) <= significance_chi2) continue;
      phasor.SetCovariance(phasor.Covariance() + 0.5 * std::norm(change) * Eigen::Matrix2d::Identity());
      result.raised = true;
      if (result.channel.empty()) result.channel = phasors[c].channel;
      if (k == 0 && std::abs(phasor.value) > 0.0 && std::abs(change) / std::abs(phasor.value) > result.change_relative) {
        result.change_relative = std::abs(change) / std::abs(phasor.value);
        result.channel = phasors[c].channel;
      }
    }
  }
  return result;
}

}  // namespace beamid::signal
