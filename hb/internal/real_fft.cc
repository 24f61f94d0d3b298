#include "hb/internal/real_fft.h"

#include <algorithm>
#include <stdexcept>

namespace beamid::hb::internal {

RealFft::RealFft(int num_samples)
    : transform_(num_samples), bins_(static_cast<std::size_t>(transform_.num_bins())) {}

void RealFft::Inverse(const Eigen::VectorXcd& phasors, Eigen::VectorXd* samples) {
  const int bins = transform_.num_bins();
  if (phasors.size() > bins - 1 && phasors.size() > 1)
    throw std::logic_error("RealFft: too many harmonics for the number of samples");
  std::fill(bins_.begin(), bins_.end(), std::complex<double>(0.0, 0.0));
  bins_[0] = phasors[0].real();
  for (Eigen::Index k = 1; k < phasors.size(); ++k)
    bins_[static_cast<std::size_t>(k)] = {0.5 * phasors[k].real(), 0.5 * phasors[k].imag()};
  samples->resize(transform_.size());
  transform_.Inverse(bins_.data(), samples->data());
}

void RealFft::Forward(const Eigen::VectorXd& samples, int num_harmonics, Eigen::VectorXcd* phasors) {
  if (samples.size() != transform_.size()) throw std::logic_error("RealFft: wrong number of samples");
  transform_.Forward(samples.data(), bins_.data());
  phasors->resize(num_harmonics + 1);
  const double scale = 2.0 / transform_.size();
  (*phasors)[0] = bins_[0].real() / transform_.size();
  for (int k = 1; k <= num_harmonics; ++k) (*phasors)[k] = scale * bins_[static_cast<std::size_t>(k)];
}

}  // namespace beamid::hb::internal
