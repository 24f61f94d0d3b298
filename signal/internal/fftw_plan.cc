#include "signal/internal/fftw_plan.h"

#include "hb/errors.h"

#include <algorithm>
#include <cstring>
#include <mutex>
#include <stdexcept>
#include <string>

#include <fftw3.h>

namespace beamid::signal::internal {
namespace {

std::mutex& PlannerMutex() {
  static std::mutex mutex;
  return mutex;
}

struct PlanDeleter {
  void operator()(fftw_plan_s* plan) const {
    std::lock_guard lock(PlannerMutex());
    fftw_destroy_plan(plan);
  }
};
struct BufferDeleter {
  void operator()(void* buffer) const { fftw_free(buffer); }
};

}  // namespace

struct RealFft::Impl {
  std::unique_ptr<double, BufferDeleter> in;
  std::unique_ptr<fftw_complex, BufferDeleter> out;
  std::unique_ptr<fftw_plan_s, PlanDeleter> plan;
};

RealFft::RealFft(int size) : impl_(std::make_unique<Impl>()), size_(size) {
  if (size < 2) throw std::invalid_argument("RealFft: size " + std::to_string(size) + " < 2");
  impl_->in.reset(fftw_alloc_real(static_cast<std::size_t>(size)));
  impl_->out.reset(fftw_alloc_complex(static_cast<std::size_t>(num_bins())));
  if (!impl_->in || !impl_->out) throw std::bad_alloc();
  std::lock_guard lock(PlannerMutex());
  impl_->plan.reset(fftw_plan_dft_r2c_1d(size, impl_->in.get(), impl_->out.get(), FFTW_ESTIMATE));
  if (!impl_->plan) throw EnvironmentError("FFTW could not plan a real transform of size " + std::to_string(size));
}

RealFft::~RealFft() = default;
RealFft::RealFft(RealFft&&) noexcept = default;
RealFft& RealFft::operator=(RealFft&&) noexcept = default;

void RealFft::Forward(const double* in, std::complex<double>* out) {
  std::memcpy(impl_->in.get(), in, sizeof(double) * static_cast<std::size_t>(size_));
  fftw_execute(impl_->plan.get());
  // fftw_complex is layout-compatible with std::complex<double> (FFTW manual §4.1.1).
  std::memcpy(static_cast<void*>(out), impl_->out.get(), sizeof(fftw_complex) * static_cast<std::size_t>(num_bins()));
}

}  // namespace beamid::signal::internal
