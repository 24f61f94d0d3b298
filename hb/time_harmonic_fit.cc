#include "hb/time_harmonic_fit.h"

#include "hb/errors.h"

#include <cmath>
#include <stdexcept>

#include <Eigen/Cholesky>

namespace beamid::hb {

TimeHarmonicFit::TimeHarmonicFit(int num_harmonics, int num_signals) : num_harmonics_(num_harmonics) {
  if (num_harmonics < 1 || num_signals < 1) throw std::invalid_argument("harmonic fit: need H >= 1 and a signal");
  const int n = 2 * num_harmonics + 1;
  normal_ = Eigen::MatrixXd::Zero(n, n);
  projected_ = Eigen::MatrixXd::Zero(n, num_signals);
  basis_.resize(n);
}

void TimeHarmonicFit::Add(double phase_rad, std::span<const double> values) {
  if (static_cast<Eigen::Index>(values.size()) != projected_.cols())
    throw std::invalid_argument("harmonic fit: wrong number of signal values");
  const std::complex<double> unit(std::cos(phase_rad), std::sin(phase_rad));
  std::complex<double> rotor = 1.0;
  basis_(0) = 1.0;
  for (int k = 1; k <= num_harmonics_; ++k) {
    rotor *= unit;
    basis_(2 * k - 1) = rotor.real();
    basis_(2 * k) = rotor.imag();
  }
  normal_.selfadjointView<Eigen::Lower>().rankUpdate(basis_);
  projected_.noalias() += basis_ * Eigen::Map<const Eigen::RowVectorXd>(values.data(), projected_.cols());
  ++num_samples_;
}

void TimeHarmonicFit::Clear() {
  normal_.setZero();
  projected_.setZero();
  num_samples_ = 0;
}

std::vector<Eigen::VectorXcd> TimeHarmonicFit::Solve() const {
  const int n = 2 * num_harmonics_ + 1;
  if (num_samples_ < n) throw NumericalError("harmonic fit: fewer samples than coefficients");
  const Eigen::MatrixXd normal = normal_.selfadjointView<Eigen::Lower>();
  const Eigen::LDLT<Eigen::MatrixXd> ldlt(normal);
  // A rank-deficient basis (samples over a tiny part of a period) shows up as
  // a pivot many orders below the largest one.
  const Eigen::VectorXd pivots = ldlt.vectorD().cwiseAbs();
  if (ldlt.info() != Eigen::Success || pivots.minCoeff() < 1e-10 * pivots.maxCoeff())
    throw NumericalError("harmonic fit: the samples do not determine the harmonics");
  const Eigen::MatrixXd coefficients = ldlt.solve(projected_);
  std::vector<Eigen::VectorXcd> phasors;
  for (Eigen::Index s = 0; s < coefficients.cols(); ++s) {
    Eigen::VectorXcd x(num_harmonics_ + 1);
    x(0) = coefficients(0, s);
    // a·cos kφ + b·sin kφ = Re((a − ib)·e^{ikφ})
    for (int k = 1; k <= num_harmonics_; ++k) x(k) = {coefficients(2 * k - 1, s), -coefficients(2 * k, s)};
    phasors.push_back(std::move(x));
  }
  return phasors;
}

void ReferenceToFundamental(std::complex<double> reference_fundamental, Eigen::VectorXcd& harmonics) {
  const double alpha = std::arg(reference_fundamental);
  for (Eigen::Index k = 1; k < harmonics.size(); ++k) harmonics(k) *= std::polar(1.0, -alpha * static_cast<double>(k));
}

}  // namespace beamid::hb
