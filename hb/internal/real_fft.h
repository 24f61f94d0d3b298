// Internal: peak phasors ↔ N samples over one period, for the harmonic
// balance's alternating frequency–time step. FFTW does not normalise; the
// scaling to the project's peak phasors is applied here
// (docs/fourier-convention.md):
//   Forward:  x_n (n < N)        → X_0 = Y_0/N, X_k = 2·Y_k/N  (k = 1..H)
//   Inverse:  X_0, X_k (k = 1..H) → x_n = X_0 + Σ Re(X_k e^{2πikn/N})
// The transform itself, and the planner's thread safety, are
// hb/fftw_real_transform.h's.
#pragma once

#include <complex>
#include <vector>

#include <Eigen/Core>

#include "hb/fftw_real_transform.h"

namespace beamid::hb::internal {

class RealFft {
 public:
  explicit RealFft(int num_samples);

  int num_samples() const { return transform_.size(); }
  // Phasors X_0..X_H (H < N/2) → N samples.
  void Inverse(const Eigen::VectorXcd& phasors, Eigen::VectorXd* samples);
  // N samples → phasors X_0..X_H.
  void Forward(const Eigen::VectorXd& samples, int num_harmonics, Eigen::VectorXcd* phasors);

 private:
  FftwRealTransform transform_;
  std::vector<std::complex<double>> bins_;  // reused: the balance transforms on every residual
};

}  // namespace beamid::hb::internal
