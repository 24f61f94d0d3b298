// Helpers that turn beamid's values into the Python objects the module
// returns: numpy arrays of a length known up front (filled by index, NaN
// where a value is missing), lists of strings, optional numbers as None.
#pragma once

#include <complex>
#include <limits>
#include <optional>
#include <string>
#include <type_traits>
#include <vector>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

namespace beamid::python {

inline constexpr double kMissing = std::numeric_limits<double>::quiet_NaN();

// A 1-D array of n values, each NaN until set.
inline pybind11::array_t<double> NanArray(std::size_t n) {
  pybind11::array_t<double> array(static_cast<pybind11::ssize_t>(n));
  auto view = array.mutable_unchecked<1>();
  for (pybind11::ssize_t i = 0; i < view.shape(0); ++i) view(i) = kMissing;
  return array;
}

// NaN, or NaN + NaN i: a value that is missing.
template <typename T>
T MissingValue() {
  if constexpr (std::is_same_v<T, std::complex<double>>)
    return {kMissing, kMissing};
  else
    return kMissing;
}

// A rows × columns array of T, each missing until set.
template <typename T>
pybind11::array_t<T> NanMatrix(std::size_t rows, std::size_t columns) {
  pybind11::array_t<T> array({static_cast<pybind11::ssize_t>(rows), static_cast<pybind11::ssize_t>(columns)});
  auto view = array.template mutable_unchecked<2>();
  for (pybind11::ssize_t i = 0; i < view.shape(0); ++i)
    for (pybind11::ssize_t j = 0; j < view.shape(1); ++j) view(i, j) = MissingValue<T>();
  return array;
}

template <typename T>
pybind11::array_t<T> ToArray(const std::vector<T>& values) {
  pybind11::array_t<T> array(static_cast<pybind11::ssize_t>(values.size()));
  auto view = array.template mutable_unchecked<1>();
  for (std::size_t i = 0; i < values.size(); ++i) view(static_cast<pybind11::ssize_t>(i)) = values[i];
  return array;
}

inline pybind11::list ToList(const std::vector<std::string>& values) {
  pybind11::list list;
  for (const std::string& v : values) list.append(v);
  return list;
}

inline pybind11::object OrNone(const std::optional<double>& value) {
  return value ? pybind11::object(pybind11::float_(*value)) : pybind11::object(pybind11::none());
}

}  // namespace beamid::python
