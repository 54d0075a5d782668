#pragma once
// Conversions between the C++ containers of the libraries and numpy arrays. Every array handed to
// Python owns its data (moved or copied), so it outlives the C++ object it came from.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <cstddef>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "shard/types.hpp"

namespace shard::python {

namespace py = pybind11;

// The vector's buffer becomes the array's: no copy.
template <class T>
py::array_t<T> to_array(std::vector<T>&& values) {
  static_assert(std::is_arithmetic_v<T>, "rows of three go through rows_array");
  auto* owned = new std::vector<T>(std::move(values));
  py::capsule owner(owned, [](void* p) { delete static_cast<std::vector<T>*>(p); });
  return py::array_t<T>(static_cast<py::ssize_t>(owned->size()), owned->data(), owner);
}

template <class T>
py::array_t<T> to_array(const std::vector<T>& values) {
  return to_array(std::vector<T>(values));
}

// Rows of three: an (n, 3) float64 array.
py::array_t<double> rows_array(const std::vector<Vec3>& rows);

// Counts (std::size_t) as int64, numpy's default integer.
py::array_t<std::int64_t> to_int64_array(const std::vector<std::size_t>& counts);

// A read-only C-contiguous view of an argument, converted once (ints to int32, floats to float64).
template <class T>
using In = py::array_t<T, py::array::c_style | py::array::forcecast>;

// The argument as a vector; throws ValueError naming `what` when it is not one-dimensional.
template <class T>
std::vector<T> to_vector(const In<T>& array, const std::string& what) {
  if (array.ndim() != 1) throw py::value_error(what + " must be a one-dimensional array");
  return std::vector<T>(array.data(), array.data() + array.size());
}

// An (n, 3) argument as rows; throws ValueError naming `what` for any other shape.
std::vector<Vec3> to_rows(const In<double>& array, const std::string& what);

}  // namespace shard::python
