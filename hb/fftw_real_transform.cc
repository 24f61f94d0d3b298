#include "hb/fftw_real_transform.h"

#include "hb/errors.h"

#include <cstring>
#include <mutex>
#include <new>
#include <stdexcept>
#include <string>

#include <fftw3.h>

namespace beamid::hb {
namespace {

std::mutex& PlannerMutex() {
  static std::mutex mutex;
  return mutex;
}

}  // namespace

struct FftwRealTransform::Impl {
  double* real = nullptr;
  fftw_complex* spectrum = nullptr;
  fftw_plan forward = nullptr;
  // Planned on the first Inverse: signal's long records only go forward.
  fftw_plan inverse = nullptr;
  ~Impl() {
    std::lock_guard lock(PlannerMutex());
    if (forward) fftw_destroy_plan(forward);
    if (inverse) fftw_destroy_plan(inverse);
    fftw_free(real);
    fftw_free(spectrum);
  }
};

FftwRealTransform::FftwRealTransform(int size) : impl_(std::make_unique<Impl>()), size_(size) {
  if (size < 2) throw std::invalid_argument("FftwRealTransform: size " + std::to_string(size) + " < 2");
  impl_->real = fftw_alloc_real(static_cast<std::size_t>(size));
  impl_->spectrum = fftw_alloc_complex(static_cast<std::size_t>(num_bins()));
  if (!impl_->real || !impl_->spectrum) throw std::bad_alloc();
  std::lock_guard lock(PlannerMutex());
  // FFTW_ESTIMATE: planning must not overwrite the buffers or take measurable time.
  impl_->forward = fftw_plan_dft_r2c_1d(size, impl_->real, impl_->spectrum, FFTW_ESTIMATE);
  if (!impl_->forward)
    throw EnvironmentError("FFTW could not plan a real transform of length " + std::to_string(size));
}

FftwRealTransform::~FftwRealTransform() = default;
FftwRealTransform::FftwRealTransform(FftwRealTransform&&) noexcept = default;
FftwRealTransform& FftwRealTransform::operator=(FftwRealTransform&&) noexcept = default;

void FftwRealTransform::Forward(const double* in, std::complex<double>* out) {
  std::memcpy(impl_->real, in, sizeof(double) * static_cast<std::size_t>(size_));
  fftw_execute(impl_->forward);
  // fftw_complex is layout-compatible with std::complex<double> (FFTW manual §4.1.1).
  std::memcpy(static_cast<void*>(out), impl_->spectrum, sizeof(fftw_complex) * static_cast<std::size_t>(num_bins()));
}

void FftwRealTransform::Inverse(const std::complex<double>* in, double* out) {
  if (!impl_->inverse) {
    std::lock_guard lock(PlannerMutex());
    impl_->inverse = fftw_plan_dft_c2r_1d(size_, impl_->spectrum, impl_->real, FFTW_ESTIMATE);
    if (!impl_->inverse)
      throw EnvironmentError("FFTW could not plan an inverse real transform of length " + std::to_string(size_));
  }
  // c2r overwrites its input: the bins are copied in on every call.
  std::memcpy(static_cast<void*>(impl_->spectrum), in, sizeof(fftw_complex) * static_cast<std::size_t>(num_bins()));
  fftw_execute(impl_->inverse);
  std::memcpy(out, impl_->real, sizeof(double) * static_cast<std::size_t>(size_));
}

}  // namespace beamid::hb
