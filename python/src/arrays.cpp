#include "arrays.hpp"

namespace shard::python {

py::array_t<double> rows_array(const std::vector<Vec3>& rows) {
  py::array_t<double> out({static_cast<py::ssize_t>(rows.size()), py::ssize_t{3}});
  auto view = out.mutable_unchecked<2>();
  for (std::size_t r = 0; r < rows.size(); ++r)
    for (py::ssize_t c = 0; c < 3; ++c) view(static_cast<py::ssize_t>(r), c) = rows[r][c];
  return out;
}

py::array_t<std::int64_t> to_int64_array(const std::vector<std::size_t>& counts) {
  return to_array(std::vector<std::int64_t>(counts.begin(), counts.end()));
}

std::vector<Vec3> to_rows(const In<double>& array, const std::string& what) {
  if (array.ndim() != 2 || array.shape(1) != 3)
    throw py::value_error(what + " must be an (n, 3) array: one row of x, y, z per entry");
  std::vector<Vec3> rows(static_cast<std::size_t>(array.shape(0)));
  auto view = array.unchecked<2>();
  for (std::size_t r = 0; r < rows.size(); ++r)
    rows[r] = Vec3(view(static_cast<py::ssize_t>(r), 0), view(static_cast<py::ssize_t>(r), 1),
                   view(static_cast<py::ssize_t>(r), 2));
  return rows;
}

}  // namespace shard::python
