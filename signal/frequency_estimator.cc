#include "signal/frequency_estimator.h"

#include "hb/errors.h"
#include "hb/fftw_real_transform.h"
#include "hb/option_checks.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include "signal/internal/harmonic_basis.h"
#include "signal/internal/text.h"

namespace beamid::signal {

double InterpolatedDftFrequency(const Eigen::Ref<const Eigen::VectorXd>& samples, double sample_rate_hz,
                                double nominal_frequency_hz, double search_band_rel) {
  const int n = static_cast<int>(samples.size());
  const double mean = samples.mean();
  Eigen::VectorXd windowed(n);
  for (int i = 0; i < n; ++i)
    windowed(i) = (samples(i) - mean) * (0.5 - 0.5 * std::cos(2.0 * std::numbers::pi * i / n));
  hb::FftwRealTransform fft(n);
  std::vector<std::complex<double>> spectrum(static_cast<std::size_t>(fft.num_bins()));
  fft.Forward(windowed.data(), spectrum.data());

  const double bin_hz = sample_rate_hz / n;
  const double nominal_bin = nominal_frequency_hz / bin_hz;
  const double half_band = std::max(3.0, search_band_rel * nominal_bin);
  const int last = fft.num_bins() - 2;
  const int lo = std::max(1, static_cast<int>(std::floor(nominal_bin - half_band)));
  const int hi = std::min(last, static_cast<int>(std::ceil(nominal_bin + half_band)));
  if (lo > hi)
    throw std::invalid_argument("the nominal frequency " + internal::FormatNumber(nominal_frequency_hz) +
                                " Hz lies outside the record's band (sample rate " +
                                internal::FormatNumber(sample_rate_hz) + " Hz)");
  int peak = lo;
  for (int j = lo; j <= hi; ++j)
    if (std::abs(spectrum[static_cast<std::size_t>(j)]) > std::abs(spectrum[static_cast<std::size_t>(peak)])) peak = j;
  const double center = std::abs(spectrum[static_cast<std::size_t>(peak)]);
  const double left = std::abs(spectrum[static_cast<std::size_t>(peak - 1)]);
  const double right = std::abs(spectrum[static_cast<std::size_t>(peak + 1)]);
  double delta = 0.0;
  if (center > 0.0) {
    const double alpha = std::max(left, right) / center;
    delta = (2.0 * alpha - 1.0) / (alpha + 1.0) * (right >= left ? 1.0 : -1.0);
  }
  return (peak + delta) * bin_hz;
}

void FrequencyEstimatorOptions::Validate() const {
  using namespace option_checks;
  RequireInRange("FrequencyEstimatorOptions.num_harmonics", num_harmonics, 1, kMaxHarmonics);
  // A band of 100 % would search down to 0 Hz.
  if (!(search_band_rel > 0.0 && search_band_rel < 1.0))
    Refuse("FrequencyEstimatorOptions.search_band_rel", FormatValue(search_band_rel), "above 0 and below 1");
  RequireAtLeast("FrequencyEstimatorOptions.max_iterations", max_iterations, 1);
  RequirePositive("FrequencyEstimatorOptions.tolerance_rel", tolerance_rel);
}

FrequencyEstimate EstimateFrequency(const Eigen::Ref<const Eigen::VectorXd>& samples, double sample_rate_hz,
                                    double nominal_frequency_hz, const FrequencyEstimatorOptions& options,
                                    double start_frequency_hz) {
  options.Validate();
  const int n = static_cast<int>(samples.size());
  const int h = options.num_harmonics;
  FrequencyEstimate estimate;
  estimate.initial_frequency_hz =
      start_frequency_hz > 0.0
          ? start_frequency_hz
          : InterpolatedDftFrequency(samples, sample_rate_hz, nominal_frequency_hz, options.search_band_rel);
  // Keep the highest modelled harmonic below Nyquist.
  const int below_nyquist = static_cast<int>(std::ceil(0.5 * sample_rate_hz / estimate.initial_frequency_hz)) - 1;
  const int usable_h = std::max(1, std::min(h, below_nyquist));
  const double bin_hz = sample_rate_hz / n;

  double frequency_hz = estimate.initial_frequency_hz;
  Eigen::VectorXd d(n);
  for (int iteration = 1; iteration <= options.max_iterations; ++iteration) {
    internal::HarmonicBasis basis(n, sample_rate_hz, frequency_hz, usable_h);
    const Eigen::VectorXd coefficients = basis.Solve(samples);
    const Eigen::VectorXd residual = samples - basis.matrix() * coefficients;
    const Eigen::MatrixXd& b = basis.matrix();
    for (Eigen::Index i = 0; i < n; ++i) {
      double sum = 0.0;
      for (int k = 1; k <= usable_h; ++k)
        sum += k * (-coefficients(2 * k - 1) * b(i, 2 * k) + coefficients(2 * k) * b(i, 2 * k - 1));
      d(i) = basis.Tau_s(i) * sum;
    }
    const Eigen::VectorXd projected = d - b * basis.normal_factor().solve(b.transpose() * d);
    const double curvature = d.dot(projected);
    // dᵀr = (P⊥d)ᵀr because Bᵀr = 0 at the linear optimum.
    double step_hz = curvature > 0.0 ? d.dot(residual) / curvature / (2.0 * std::numbers::pi) : 0.0;
    // Trust region: the start is within a fraction of a bin; never jump further.
    step_hz = std::clamp(step_hz, -0.5 * bin_hz, 0.5 * bin_hz);
    frequency_hz += step_hz;
    estimate.iterations = iteration;
    const double noise_variance = residual.squaredNorm() / std::max(1.0, static_cast<double>(n - b.cols() - 1));
    estimate.std_hz = curvature > 0.0 ? std::sqrt(noise_variance / curvature) / (2.0 * std::numbers::pi) : 0.0;
    const Eigen::MatrixXd covariance = basis.InverseNormalMatrix();
    estimate.fundamental_amplitude = std::abs(internal::HarmonicBasis::Phasor(coefficients, 1));
    estimate.fundamental_std = std::sqrt(noise_variance * 0.5 * (covariance(1, 1) + covariance(2, 2)));
    if (std::abs(step_hz) <= options.tolerance_rel * frequency_hz || std::abs(step_hz) < 1e-3 * estimate.std_hz) {
      estimate.frequency_hz = frequency_hz;
      return estimate;
    }
  }
  throw NumericalError("the excitation frequency did not converge in " + std::to_string(options.max_iterations) +
                           " Gauss-Newton iterations (start " + internal::FormatNumber(estimate.initial_frequency_hz) +
                           " Hz, last " + internal::FormatNumber(frequency_hz) + " Hz)");
}

}  // namespace beamid::signal
