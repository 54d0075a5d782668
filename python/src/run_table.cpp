#include "run_table.hpp"

#include <pybind11/stl.h>

#include <type_traits>

#include "arrays.hpp"

namespace shard::python {

pybind11::dict table_dict(RunTable&& table) {
  py::dict columns, figures;
  for (auto& [name, column] : table.columns)
    columns[py::str(name)] = std::visit(
        [](auto& values) -> py::object {
          using T = typename std::decay_t<decltype(values)>::value_type;
          if constexpr (std::is_same_v<T, Vec3>) return rows_array(values);
          else if constexpr (std::is_same_v<T, std::string>) return py::cast(values);
          else return to_array(std::move(values));
        },
        column);
  for (const auto& [name, figure] : table.figures)
    figures[py::str(name)] = std::visit([](const auto& value) { return py::cast(value); }, figure);
  py::dict out;
  out["columns"] = columns;
  out["figures"] = figures;
  return out;
}

}  // namespace shard::python
