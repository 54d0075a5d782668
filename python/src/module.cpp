// The extension module under the pure-Python package `shard` (python/shard/): thin bindings of the
// libraries' own functions, returning plain dicts of numpy arrays that the package wraps in classes.
#include "bindings.hpp"

PYBIND11_MODULE(_shard, m) {
  m.doc() = "Bindings of Shard's run driver, run-file reader and fragment analysis";
  shard::python::bind_errors(m);
  shard::python::bind_run(m);
  shard::python::bind_run_file(m);
  shard::python::bind_analysis(m);
}
