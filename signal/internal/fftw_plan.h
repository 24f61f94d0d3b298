// Move-only owner of an FFTW real-to-complex plan and its aligned buffers.
// Planning (FFTW_ESTIMATE) is serialised by a process-wide mutex because only
// fftw_execute is thread-safe; each RealFft object is used by one thread.
// Scaling: Forward returns FFTW's unnormalised Y_j = Σ_n x_n e^{−2πijn/N},
// j = 0..N/2 (see docs/fourier-convention.md for X_k = 2·Y_k/N).
#pragma once

#include <complex>
#include <memory>

namespace beamid::signal::internal {

class RealFft {
 public:
  explicit RealFft(int size);
  ~RealFft();
  RealFft(RealFft&&) noexcept;
  RealFft& operator=(RealFft&&) noexcept;
  RealFft(const RealFft&) = delete;
  RealFft& operator=(const RealFft&) = delete;

  int size() const { return size_; }
  int num_bins() const { return size_ / 2 + 1; }
  // in: size() values; out: num_bins() values.
  void Forward(const double* in, std::complex<double>* out);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  int size_ = 0;
};

}  // namespace beamid::signal::internal
