// FFTW's real discrete Fourier transform of one length N, as the project's one
// owner of FFTW plans: hb's harmonic balance (through hb/internal/real_fft.h,
// which adds the peak-phasor scaling) and signal's spectra both use it.
// One owner, because FFTW's planner is process-wide and not thread-safe:
// every plan made or destroyed here goes through one mutex, which two
// wrappers with a mutex each could not guarantee. Executing plans of distinct
// objects concurrently is safe; one object belongs to one thread.
// The transforms are FFTW's, unnormalised (docs/fourier-convention.md says how
// the project's phasors follow from them), planned with FFTW_ESTIMATE so that
// planning neither takes measurable time nor depends on timing: the same N
// gives the same plan, and so the same bits, in every run.
#pragma once

#include <complex>
#include <memory>

namespace beamid::hb {

class FftwRealTransform {
 public:
  // Throws std::invalid_argument for size < 2 and EnvironmentError
  // (hb/errors.h) when FFTW cannot plan.
  explicit FftwRealTransform(int size);
  ~FftwRealTransform();
  FftwRealTransform(FftwRealTransform&&) noexcept;
  FftwRealTransform& operator=(FftwRealTransform&&) noexcept;
  FftwRealTransform(const FftwRealTransform&) = delete;
  FftwRealTransform& operator=(const FftwRealTransform&) = delete;

  int size() const { return size_; }
  int num_bins() const { return size_ / 2 + 1; }
  // r2c: size() samples x_n → num_bins() bins Y_j = Σ_n x_n e^{−2πijn/N}.
  void Forward(const double* in, std::complex<double>* out);
  // c2r: num_bins() bins Y_j → size() samples x_n = Σ_{j<N} Y_j e^{2πijn/N}
  // (with Y_{N−j} = conj Y_j), N times the inverse DFT. The imaginary parts
  // of Y_0 and, for even N, of Y_{N/2} are ignored.
  void Inverse(const std::complex<double>* in, double* out);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  int size_ = 0;
};

}  // namespace beamid::hb
