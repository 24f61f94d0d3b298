// Equality for round trips of the file formats: the same bits (a writer that
// rounds fails), NaN equal to NaN (a statistic the fit could not give), and
// the same for phasors, vectors and Eigen matrices, with a message that says
// which entry differs.
#pragma once

#include <bit>
#include <cmath>
#include <complex>
#include <cstdint>
#include <vector>

#include <Eigen/Core>
#include <gtest/gtest.h>

namespace beamid::testing {

inline ::testing::AssertionResult Same(double a, double b) {
  if (std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b) || (std::isnan(a) && std::isnan(b)))
    return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << a << " != " << b;
}

inline ::testing::AssertionResult Same(std::complex<double> a, std::complex<double> b) {
  if (Same(a.real(), b.real()) && Same(a.imag(), b.imag())) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << a << " != " << b;
}

template <typename T>
::testing::AssertionResult Same(const std::vector<T>& a, const std::vector<T>& b) {
  if (a.size() != b.size()) return ::testing::AssertionFailure() << a.size() << " != " << b.size() << " entries";
  for (std::size_t i = 0; i < a.size(); ++i)
    if (!Same(a[i], b[i])) return ::testing::AssertionFailure() << "entry " << i << ": " << a[i] << " != " << b[i];
  return ::testing::AssertionSuccess();
}

template <typename Derived>
::testing::AssertionResult Same(const Eigen::DenseBase<Derived>& a, const Eigen::DenseBase<Derived>& b) {
  if (a.rows() != b.rows() || a.cols() != b.cols())
    return ::testing::AssertionFailure() << a.rows() << "×" << a.cols() << " != " << b.rows() << "×" << b.cols();
  for (Eigen::Index r = 0; r < a.rows(); ++r)
    for (Eigen::Index c = 0; c < a.cols(); ++c)
      if (!Same(a(r, c), b(r, c)))
        return ::testing::AssertionFailure() << "(" << r << ", " << c << "): " << a(r, c) << " != " << b(r, c);
  return ::testing::AssertionSuccess();
}

}  // namespace beamid::testing
