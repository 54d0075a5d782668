#pragma once
// A RunTable (shard/run_file.hpp), the form in which the analysis stores its tables, as a dict:
// "columns" (name -> numpy array; rows of three as (n, 3), text as a list of str) and "figures".
#include <pybind11/pybind11.h>

#include "shard/run_file.hpp"

namespace shard::python {

pybind11::dict table_dict(RunTable&& table);

}  // namespace shard::python
