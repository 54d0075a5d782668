// shard._shard.run: one run of a scene in this process, composed as `shard run` composes it
// (apps/src/run_command.cpp): the scene's stop rules and fragment labels, Ctrl-C with a checkpoint,
// the closing report and the curve CSV. The GIL is released while the driver steps, so other
// Python threads go on; the driver's lines are gathered and handed back with the result.
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <iostream>
#include <mutex>
#include <optional>

#include "arrays.hpp"
#include "bindings.hpp"
#include "shard/driver/checkpoint_writer.hpp"
#include "shard/driver/progress_printer.hpp"
#include "shard/driver/run_driver.hpp"
#include "shard/driver/run_report.hpp"
#include "shard/driver/scene_rules.hpp"
#include "shard/driver/stop_rules.hpp"
#include "shard/plugin_host.hpp"

namespace shard::python {
namespace {

namespace fs = std::filesystem;

// A Python value as the typed override the scene takes; lists of numbers and of strings are TOML
// arrays (as `--set key=[...]` parses them).
SceneOverride::Value override_value(const std::string& key, const py::handle& value) {
  if (py::isinstance<py::bool_>(value)) return value.cast<bool>();
  if (py::isinstance<py::int_>(value)) return value.cast<std::int64_t>();
  if (py::isinstance<py::float_>(value)) return value.cast<double>();
  if (py::isinstance<py::str>(value)) return value.cast<std::string>();
  if (py::isinstance<py::sequence>(value)) {
    const auto items = value.cast<py::sequence>();
    bool all_text = py::len(items) > 0;
    for (const auto& item : items) all_text = all_text && py::isinstance<py::str>(item);
    if (all_text) return items.cast<std::vector<std::string>>();
    try {
      return items.cast<std::vector<double>>();
    } catch (const py::cast_error&) {
    }
  }
  throw py::type_error("override '" + key + "': " + py::str(py::type::of(value)).cast<std::string>() +
                       " is no scene value. Fix: give a bool, int, float, str, or a list of numbers or of strings");
}

SceneOverrides to_overrides(const std::vector<std::pair<std::string, py::object>>& items) {
  SceneOverrides out;
  for (const auto& [key, value] : items) out.emplace_back(key, override_value(key, value));
  return out;
}

const char* stop_name(driver::StopReason stop) {
  switch (stop) {
    case driver::StopReason::Duration: return "duration";
    case driver::StopReason::LoadDrop: return "load_drop";
    case driver::StopReason::MaxDisplacement: return "max_displacement";
    case driver::StopReason::Interrupted: return "interrupted";
    case driver::StopReason::Observer: return "observer";
    case driver::StopReason::Rest: return "rest";
  }
  return "unknown";
}

py::dict result_dict(driver::RunResult&& r, std::vector<std::string>&& log) {
  py::dict d;
  d["output"] = r.output;
  d["steps"] = r.steps;
  d["time"] = r.time;
  d["dt"] = r.dt;
  d["particles"] = r.particles;
  d["bonds_initial"] = r.bonds_initial;
  d["bonds_broken"] = r.bonds_broken;
  d["curve_time"] = to_array(std::move(r.curve.time));
  d["curve_displacement"] = to_array(std::move(r.curve.displacement));
  d["curve_load"] = to_array(std::move(r.curve.force));
  d["peak_load"] = r.peak_load;
  d["displacement_at_peak"] = r.displacement_at_peak;
  d["final_displacement"] = r.final_displacement;
  d["kinetic_before_break"] = to_array(std::move(r.kinetic_before_break));
  d["elastic_before_break"] = to_array(std::move(r.elastic_before_break));
  d["max_kinetic_to_elastic"] = r.max_kinetic_to_elastic;
  d["fragment_particles"] = to_int64_array(r.fragment_particles);
  d["wall_seconds"] = r.wall_seconds;
  d["stop"] = stop_name(r.stop);
  d["stop_reason"] = r.stop_reason;
  d["checkpoint"] = r.checkpoint.empty() ? py::object(py::none()) : py::cast(r.checkpoint);
  d["checkpoint_step"] = r.checkpoint_step;
  d["restarted_from"] = r.restarted_from;
  d["interrupt_signal"] = r.interrupt_signal;
  d["log"] = std::move(log);
  return d;
}

// The driver's lines, kept for the caller and echoed to stderr when asked; called without the GIL.
class LineLog {
 public:
  explicit LineLog(bool echo) : echo_(echo) {}
  void add(const std::string& line) {
    const std::lock_guard lock(mutex_);
    lines_.push_back(line);
    if (echo_) std::cerr << line << '\n';
  }
  std::vector<std::string> take() { return std::move(lines_); }

 private:
  bool echo_;
  std::mutex mutex_;
  std::vector<std::string> lines_;
};

struct RunRequest {
  driver::RunSpec spec;
  std::vector<fs::path> plugin_dirs;
  int checkpoint_every = 1;
  bool progress = false;
};

driver::RunResult run_request(const RunRequest& request, LineLog& lines) {
  PluginHost host;
  for (const auto& refused : host.load_directories(PluginHost::default_search_path(request.plugin_dirs)))
    lines.add("warning: " + refused);
  const auto info = [&](const std::string& text) { lines.add(text); };
  const driver::RunLog log{info, [&](const std::string& text) { lines.add("warning: " + text); }};
  // The order of `shard run`: a stop rule ends the run before the progress line of its row, the
  // labels are in each frame before a checkpoint follows it.
  driver::SceneRules scene_rules;
  driver::CheckpointWriter checkpoints(request.checkpoint_every);
  driver::InterruptStop interrupt;
  driver::ProgressPrinter progress(std::cerr);
  driver::RunReport report(info);
  driver::CurveCsvWriter curve(info);
  std::vector<driver::RunObserver*> observers = scene_rules.observers();
  observers.insert(observers.end(), {&checkpoints, &interrupt});
  if (request.progress) observers.push_back(&progress);
  observers.insert(observers.end(), {&report, &curve});
  return driver::run(request.spec, host, observers, log);
}

py::dict run(const fs::path& scene, const std::vector<std::pair<std::string, py::object>>& overrides,
             const std::vector<std::string>& assignments, const fs::path& out, const fs::path& restart,
             int threads, int checkpoint_every, const std::vector<fs::path>& plugin_dirs, bool progress, bool echo) {
  RunRequest request;
  request.spec.scene = scene;
  request.spec.overrides = parse_overrides(assignments);
  const SceneOverrides typed = to_overrides(overrides);
  request.spec.overrides.insert(request.spec.overrides.end(), typed.begin(), typed.end());
  request.spec.out_dir = out;
  request.spec.restart = restart;
  request.spec.threads = threads;
  request.plugin_dirs = plugin_dirs;
  request.checkpoint_every = checkpoint_every;
  request.progress = progress;
  LineLog lines(echo);
  driver::RunResult result;
  {
    const py::gil_scoped_release free_other_threads;
    result = run_request(request, lines);
  }
  return result_dict(std::move(result), lines.take());
}

}  // namespace

void bind_run(py::module_& m) {
  m.def("run", &run, py::arg("scene"), py::arg("overrides"), py::arg("assignments"), py::arg("out"),
        py::arg("restart"), py::arg("threads"), py::arg("checkpoint_every"), py::arg("plugin_dirs"),
        py::arg("progress"), py::arg("echo"),
        "Runs a scene to its end or a stop rule; returns the driver's result as a dict");
  m.def(
      "plugin_search_path",
      [](const std::vector<fs::path>& dirs) { return PluginHost::default_search_path(dirs); },
      py::arg("plugin_dirs"), "The folders searched for plugins, in priority order, as `shard run` searches them");
}

}  // namespace shard::python
