// Each error type the libraries throw for bad input becomes a Python exception of the same name,
// so a script can catch a scene mistake apart from a numerical blow-up.
#include "bindings.hpp"
#include "shard/checkpoint.hpp"
#include "shard/driver/numerical_health.hpp"
#include "shard/output.hpp"
#include "shard/plugin_host.hpp"
#include "shard/scene.hpp"

namespace shard::python {

void bind_errors(pybind11::module_& m) {
  // A bad scene, override, plugin name or file is the caller's input: ValueError. A blow-up and a
  // failed write are the run's: RuntimeError.
  pybind11::register_exception<SceneError>(m, "SceneError", PyExc_ValueError);
  pybind11::register_exception<PluginError>(m, "PluginError", PyExc_ValueError);
  pybind11::register_exception<OutputError>(m, "OutputError", PyExc_OSError);
  pybind11::register_exception<CheckpointError>(m, "CheckpointError", PyExc_OSError);
  pybind11::register_exception<NumericalError>(m, "NumericalError", PyExc_RuntimeError);
}

}  // namespace shard::python
