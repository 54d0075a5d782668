#pragma once
// The parts of the extension module `shard._shard`, one file each; module.cpp calls them in turn.
#include <pybind11/pybind11.h>

namespace shard::python {

void bind_errors(pybind11::module_& m);    // C++ error types as Python exceptions
void bind_run(pybind11::module_& m);       // the in-process run driver
void bind_run_file(pybind11::module_& m);  // the run-file reader
void bind_analysis(pybind11::module_& m);  // fragments, size distributions, per-body statistics

}  // namespace shard::python
