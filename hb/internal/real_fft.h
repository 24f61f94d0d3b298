// Internal: a move-only owner of one pair of FFTW real plans (r2c and c2r) of
// length N with their aligned buffers. FFTW does not normalise; the scaling to
// the project's peak phasors is applied here (docs/fourier-convention.md):
//   Forward:  x_n (n < N)        → X_0 = Y_0/N, X_k = 2·Y_k/N  (k = 1..H)
//   Inverse:  X_0, X_k (k = 1..H) → x_n = X_0 + Σ Re(X_k e^{2πikn/N})
// Planning goes through a global mutex (FFTW's planner is not thread-safe);
// execution on distinct objects is.
#pragma once

#include <complex>
#include <memory>

#include <Eigen/Core>

namespace beamid::hb::internal {

class RealFft {
 public:
  explicit RealFft(int num_samples);
  ~RealFft();
  RealFft(RealFft&&) noexcept;
  RealFft& operator=(RealFft&&) noexcept;
  RealFft(const RealFft&) = delete;
  RealFft& operator=(const RealFft&) = delete;

  int num_samples() const { return num_samples_; }
  // Phasors X_0..X_H (H < N/2) → N samples.
  void Inverse(const Eigen::VectorXcd& phasors, Eigen::VectorXd* samples);
  // N samples → phasors X_0..X_H.
  void Forward(const Eigen::VectorXd& samples, int num_harmonics, Eigen::VectorXcd* phasors);

 private:
  struct Plans;
  int num_samples_ = 0;
  std::unique_ptr<Plans> plans_;
};

}  // namespace beamid::hb::internal
