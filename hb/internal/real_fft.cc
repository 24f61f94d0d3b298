#include "hb/internal/real_fft.h"

#include "hb/errors.h"

#include <cstring>
#include <mutex>
#include <stdexcept>

#include <fftw3.h>

namespace beamid::hb::internal {
namespace {
std::mutex& PlannerMutex() {
  static std::mutex mutex;
  return mutex;
}
}  // namespace

struct RealFft::Plans {
  double* real = nullptr;
  fftw_complex* spectrum = nullptr;
  fftw_plan forward = nullptr;
  fftw_plan inverse = nullptr;
  ~Plans() {
    std::lock_guard lock(PlannerMutex());
    if (forward) fftw_destroy_plan(forward);
    if (inverse) fftw_destroy_plan(inverse);
    fftw_free(real);
    fftw_free(spectrum);
  }
};

RealFft::RealFft(int num_samples) : num_samples_(num_samples), plans_(std::make_unique<Plans>()) {
  if (num_samples < 2) throw std::invalid_argument("RealFft needs at least 2 samples");
  std::lock_guard lock(PlannerMutex());
  plans_->real = fftw_alloc_real(num_samples);
  plans_->spectrum = fftw_alloc_complex(num_samples / 2 + 1);
  // FFTW_ESTIMATE: planning must not overwrite buffers or take measurable time.
  plans_->forward = fftw_plan_dft_r2c_1d(num_samples, plans_->real, plans_->spectrum, FFTW_ESTIMATE);
  plans_->inverse = fftw_plan_dft_c2r_1d(num_samples, plans_->spectrum, plans_->real, FFTW_ESTIMATE);
  if (!plans_->real || !plans_->spectrum || !plans_->forward || !plans_->inverse)
    throw EnvironmentError("FFTW could not plan a real transform of length " + std::to_string(num_samples));
}

RealFft::~RealFft() = default;
RealFft::RealFft(RealFft&&) noexcept = default;
RealFft& RealFft::operator=(RealFft&&) noexcept = default;

void RealFft::Inverse(const Eigen::VectorXcd& phasors, Eigen::VectorXd* samples) {
  const int bins = num_samples_ / 2 + 1;
  if (phasors.size() > bins - 1 && phasors.size() > 1)
    throw std::logic_error("RealFft: too many harmonics for the number of samples");
  std::memset(plans_->spectrum, 0, sizeof(fftw_complex) * bins);
  plans_->spectrum[0][0] = phasors[0].real();
  for (Eigen::Index k = 1; k < phasors.size(); ++k) {
    plans_->spectrum[k][0] = 0.5 * phasors[k].real();
    plans_->spectrum[k][1] = 0.5 * phasors[k].imag();
  }
  fftw_execute(plans_->inverse);  // c2r overwrites its input; we rebuild it every call
  samples->resize(num_samples_);
  std::memcpy(samples->data(), plans_->real, sizeof(double) * num_samples_);
}

void RealFft::Forward(const Eigen::VectorXd& samples, int num_harmonics, Eigen::VectorXcd* phasors) {
  if (samples.size() != num_samples_) throw std::logic_error("RealFft: wrong number of samples");
  std::memcpy(plans_->real, samples.data(), sizeof(double) * num_samples_);
  fftw_execute(plans_->forward);
  phasors->resize(num_harmonics + 1);
  const double scale = 2.0 / num_samples_;
  (*phasors)[0] = plans_->spectrum[0][0] / num_samples_;
  for (int k = 1; k <= num_harmonics; ++k)
    (*phasors)[k] = scale * std::complex<double>(plans_->spectrum[k][0], plans_->spectrum[k][1]);
}

}  // namespace beamid::hb::internal
