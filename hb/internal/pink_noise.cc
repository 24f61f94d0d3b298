#include "hb/internal/pink_noise.h"

#include <cmath>
#include <complex>

#include "hb/internal/real_fft.h"

namespace beamid::hb::internal {

void AddPinkNoise(double rms, std::mt19937_64& rng, Eigen::Ref<Eigen::VectorXd> samples) {
  const int n = static_cast<int>(samples.size());
  if (!(rms > 0.0) || n < 3) return;
  // RealFft holds harmonics 1..⌊N/2⌋ − 1: the top bin (Nyquist for even N) is left out.
  const int harmonics = n / 2 - 1;
  std::normal_distribution<double> gaussian(0.0, 1.0);
  Eigen::VectorXcd phasors = Eigen::VectorXcd::Zero(harmonics + 1);
  for (int k = 1; k <= harmonics; ++k) {
    const double re = gaussian(rng);
    const double im = gaussian(rng);
    // Power ∝ |X_k|² ∝ 1/k: 1/f.
    phasors(k) = std::complex<double>(re, im) / std::sqrt(static_cast<double>(k));
  }
  RealFft fft(n);
  Eigen::VectorXd drift(n);
  fft.Inverse(phasors, &drift);
  const double drawn_rms = std::sqrt(drift.squaredNorm() / n);
  if (drawn_rms > 0.0) samples += (rms / drawn_rms) * drift;
}

}  // namespace beamid::hb::internal
