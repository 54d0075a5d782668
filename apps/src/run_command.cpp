#include "shard/app/run_command.hpp"

#include <fmt/format.h>
#include <fmt/ostream.h>

#include <csignal>
#include <ostream>

#include "shard/driver/checkpoint_writer.hpp"
#if SHARD_MPI_RUN
#include "shard/driver/distributed_run.hpp"
#endif
#include "shard/driver/scene_rules.hpp"
#include "shard/driver/progress_printer.hpp"
#include "shard/driver/run_driver.hpp"
#include "shard/driver/run_report.hpp"
#include "shard/driver/stop_rules.hpp"
#include "shard/plugin_host.hpp"

namespace shard {
namespace {

class SignalGuard {
 public:
  SignalGuard(int signal, void (*handler)(int)) : signal_(signal), previous_(std::signal(signal, handler)) {}
  ~SignalGuard() { std::signal(signal_, previous_); }
  SignalGuard(const SignalGuard&) = delete;
  SignalGuard& operator=(const SignalGuard&) = delete;

 private:
  int signal_;
  void (*previous_)(int);
};

}  // namespace

void load_plugins(PluginHost& host, const std::vector<std::filesystem::path>& dirs, std::ostream& log) {
  for (const auto& refused : host.load_directories(PluginHost::default_search_path(dirs)))
    fmt::print(log, "warning: {}\n", refused);
}

RunSummary run_scene(const RunOptions& options, std::ostream& log_stream) {
  // A full disk or a file-size limit must surface as a write error, not kill the process.
  const SignalGuard file_size_guard(SIGXFSZ, SIG_IGN);
  auto line = [&](const std::string& text) {
    if (!options.quiet) fmt::print(log_stream, "{}\n", text);
  };
  PluginHost host;
  load_plugins(host, options.plugin_dirs, log_stream);

  driver::RunSpec spec;
  spec.scene = options.scene;
  spec.overrides = options.overrides;
  spec.out_dir = options.out_dir;
  spec.restart = options.restart;
  spec.threads = options.threads;
  spec.health_every = options.health_every;
  const driver::RunLog log{line, [&](const std::string& text) { fmt::print(log_stream, "warning: {}\n", text); }};

  // The order is the order of the hooks: a stop rule ends the run before the progress line of
  // its row, the labels are in each frame before a checkpoint follows it.
  driver::SceneRules scene_rules;
  driver::CheckpointWriter checkpoints(options.checkpoint_every);
  driver::InterruptStop interrupt(options.interrupt_at_step);
  driver::ProgressPrinter progress(log_stream);
  driver::RunReport report(line);
  driver::CurveCsvWriter curve(line);
  std::vector<driver::RunObserver*> observers = scene_rules.observers();
  observers.insert(observers.end(), {&checkpoints, &interrupt});
#if SHARD_MPI_RUN
  // Under mpirun the run is decomposed over the ranks; rank 0 prints and writes for it.
  if (options.decompose_under_mpirun && driver::launched_by_mpi()) {
    const driver::MpiSession mpi;
    if (mpi.rank() == 0) {
      if (!options.quiet) observers.push_back(&progress);
      observers.insert(observers.end(), {&report, &curve});
    }
    try {
      return driver::run_distributed(spec, host, observers, log);
    } catch (const std::exception& e) {
      driver::abort_job(e.what());  // a rank left alone in a collective call would wait forever
    }
  }
#endif
  if (!options.quiet) observers.push_back(&progress);
  observers.insert(observers.end(), {&report, &curve});
  return driver::run(spec, host, observers, log);
}

}  // namespace shard
