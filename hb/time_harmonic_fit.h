// Least-squares multi-harmonic fit of sampled signals whose fundamental phase
// φ(t) is known exactly (a simulation knows its generator):
//     x(t_n) ≈ X_0 + Σ_{k=1..H} Re(X_k · e^{i k φ(t_n)})
// in the convention of docs/fourier-convention.md (X_k complex peak phasors).
// The samples need not span an integer number of periods. Used by the
// simulator to decide when a step has settled and to compute the noise-free
// truth phasors; signal/ extracts phasors from recordings independently.
#pragma once

#include <complex>
#include <span>
#include <vector>

#include <Eigen/Core>

namespace beamid::hb {

class TimeHarmonicFit {
 public:
  // num_harmonics: H ≥ 1; num_signals: how many signals share the samples.
  TimeHarmonicFit(int num_harmonics, int num_signals);

  // One sample of every signal at fundamental phase φ [rad].
  void Add(double phase_rad, std::span<const double> values);
  int NumSamples() const { return num_samples_; }
  void Clear();

  // Per signal: [X_0, X_1, …, X_H]. Throws std::runtime_error if the samples
  // do not determine the 2H+1 coefficients (too few, or too little of a period).
  std::vector<Eigen::VectorXcd> Solve() const;

 private:
  int num_harmonics_;
  int num_samples_ = 0;
  Eigen::MatrixXd normal_;     // Σ b·bᵀ, b = [1, cos φ, sin φ, …, cos Hφ, sin Hφ]
  Eigen::MatrixXd projected_;  // Σ b·xᵀ, one column per signal
  Eigen::VectorXd basis_;
};

// Rotates phasors [X_0 … X_H] so that the reference fundamental is real and
// positive: X_k ← X_k · e^{−ikα}, α = arg(reference X_1).
void ReferenceToFundamental(std::complex<double> reference_fundamental, Eigen::VectorXcd& harmonics);

}  // namespace beamid::hb
