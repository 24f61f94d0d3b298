#include "signal/harmonic_fit.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "hb/fftw_real_transform.h"

#include "signal/internal/harmonic_basis.h"

namespace beamid::signal {
namespace {

constexpr int kExcludedBins = 3;     // around each multiple of f (fit notch and leakage)
constexpr double kMinHalfBandBins = 16.0;
constexpr int kMinNoiseBins = 4;

// Correlation of a Hann periodogram's values one and two bins apart, for
// white noise (the window's transform is three taps, −1/4, 1/2, −1/4).
constexpr double kHannNeighbourCorrelation = 4.0 / 9.0;
constexpr double kHannSecondNeighbourCorrelation = 1.0 / 36.0;

// σ_k² and their degrees of freedom ν_k (header), k = 1..h, from the Hann
// periodogram of one residual.
void LocalNoiseFloor(const Eigen::VectorXd& residual, double bin_per_harmonic, int h, double fallback_variance,
                     double fallback_dof, hb::FftwRealTransform& fft, Eigen::VectorXd& windowed,
                     std::vector<std::complex<double>>& spectrum, ChannelFit* channel) {
  const Eigen::Index n = residual.size();
  double window_power = 0.0;
  for (Eigen::Index i = 0; i < n; ++i) {
    const double w = 0.5 - 0.5 * std::cos(2.0 * std::numbers::pi * static_cast<double>(i) / static_cast<double>(n));
    windowed(i) = w * residual(i);
    window_power += w * w;
  }
  fft.Forward(windowed.data(), spectrum.data());
  const int last_bin = fft.num_bins() - 2;  // skip Nyquist
  channel->noise_variance.resize(h);
  channel->noise_dof.resize(h);
  const double half_band = std::max(0.5 * bin_per_harmonic, kMinHalfBandBins);
  for (int k = 1; k <= h; ++k) {
    const double center = k * bin_per_harmonic;
    const int lo = std::max(1, static_cast<int>(std::ceil(center - half_band)));
    const int hi = std::min(last_bin, static_cast<int>(std::floor(center + half_band)));
    double sum = 0.0;
    int count = 0, one_apart = 0, two_apart = 0, last = -10, before_last = -10;
    for (int j = lo; j <= hi; ++j) {
      const double nearest_multiple = std::round(j / bin_per_harmonic) * bin_per_harmonic;
      if (std::abs(j - nearest_multiple) < kExcludedBins) continue;
      sum += std::norm(spectrum[static_cast<std::size_t>(j)]);
      ++count;
      one_apart += last == j - 1;
      two_apart += last == j - 2 || before_last == j - 2;
      before_last = last;
      last = j;
    }
    const bool enough = count >= kMinNoiseBins;
    channel->noise_variance(k - 1) = enough ? sum / count / window_power : fallback_variance;
    channel->noise_dof(k - 1) =
        enough ? 2.0 * count * count /
                     (count + 2.0 * kHannNeighbourCorrelation * one_apart +
                      2.0 * kHannSecondNeighbourCorrelation * two_apart)
               : fallback_dof;
  }
}

}  // namespace

double StudentVarianceFactor(double dof) { return dof > 3.0 ? dof / (dof - 2.0) : 3.0; }

HarmonicFit FitHarmonics(const Eigen::Ref<const Eigen::MatrixXd>& samples, double sample_rate_hz,
                         double frequency_hz, int num_harmonics) {
  const int n = static_cast<int>(samples.rows());
  const int below_nyquist = static_cast<int>(std::ceil(0.5 * sample_rate_hz / frequency_hz)) - 1;
  const int h = std::max(1, std::min(num_harmonics, below_nyquist));
  internal::HarmonicBasis basis(n, sample_rate_hz, frequency_hz, h);
  const Eigen::MatrixXd coefficients = basis.Solve(samples);
  const Eigen::MatrixXd unit_covariance = basis.InverseNormalMatrix();
  const double bin_per_harmonic = frequency_hz * n / sample_rate_hz;
  const double dof = std::max(1.0, static_cast<double>(n - basis.matrix().cols()));

  HarmonicFit fit;
  fit.frequency_hz = frequency_hz;
  fit.num_harmonics = h;
  hb::FftwRealTransform fft(n);
  Eigen::VectorXd windowed(n);
  std::vector<std::complex<double>> spectrum(static_cast<std::size_t>(fft.num_bins()));
  Eigen::VectorXd residual(n);
  for (Eigen::Index c = 0; c < samples.cols(); ++c) {
    residual.noalias() = samples.col(c) - basis.matrix() * coefficients.col(c);
    ChannelFit channel;
    channel.mean = coefficients(0, c);
    channel.residual_rms = std::sqrt(residual.squaredNorm() / n);
    LocalNoiseFloor(residual, bin_per_harmonic, h, residual.squaredNorm() / dof, dof, fft, windowed, spectrum,
                    &channel);
    channel.phasors.resize(h);
    for (int k = 1; k <= h; ++k) {
      channel.phasors(k - 1) = internal::HarmonicBasis::Phasor(coefficients.col(c), k);
      // (a, b) -> (Re X, Im X) = (a, −b) flips the sign of the covariance term.
      Eigen::Matrix2d covariance = unit_covariance.block<2, 2>(2 * k - 1, 2 * k - 1);
      covariance(0, 1) = covariance(1, 0) = -covariance(0, 1);
      channel.covariances.push_back(channel.noise_variance(k - 1) * StudentVarianceFactor(channel.noise_dof(k - 1)) *
                                    covariance);
    }
    fit.channels.push_back(std::move(channel));
  }
  return fit;
}

}  // namespace beamid::signal
