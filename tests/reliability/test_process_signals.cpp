// The real `shard run` process: SIGKILL leaves a run file that opens with every frame flushed
// before the kill, and --restart then ends bit-identical to an uninterrupted run; SIGINT and
// SIGTERM stop cleanly (exit 130, 143) after writing a checkpoint.
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <thread>
#include <utility>

#include "reliability_fixtures.hpp"
#include "shard/run_file.hpp"

using namespace shard;
using namespace shard::test;

namespace {

// ~11,500 steps: long enough to be killed mid-run, short enough for the suite.
const std::vector<std::string> kArgs = {"run", (kScenes / "crush_cube.toml").string(), "--threads", "1", "--quiet",
                                        "--set", "simulation.duration=0.03", "--set", "stop.max_displacement=0",
                                        "--set", "wall.plate.velocity=[0, 0, -0.05]"};

std::string quoted_args() {
  std::string s;
  for (const auto& a : kArgs) s += " '" + a + "'";
  return s;
}

pid_t start_shard(const std::filesystem::path& dir) {
  const pid_t pid = fork();
  if (pid == 0) {
    if (chdir(dir.c_str()) != 0) _exit(127);
    std::vector<char*> argv;
    std::string program = kShard.string();
    argv.push_back(program.data());
    std::vector<std::string> args = kArgs;
    for (auto& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    freopen("stderr.txt", "w", stderr);
    execv(program.c_str(), argv.data());
    _exit(127);
  }
  return pid;
}

// Waits until the run has written a few checkpoints (each follows a flushed frame).
void wait_for_checkpoints(const std::filesystem::path& dir, pid_t pid) {
  const auto checkpoint = dir / "run.checkpoint.h5";
  for (int k = 0; k < 600; ++k) {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    if (std::filesystem::exists(checkpoint) && read_checkpoint(checkpoint).number("frames_written") >= 4) return;
    int status = 0;
    REQUIRE(waitpid(pid, &status, WNOHANG) == 0);  // still running
  }
  FAIL("the run wrote no checkpoint within 12 s");
}

int wait_exit(pid_t pid) {
  int status = 0;
  waitpid(pid, &status, 0);
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

}  // namespace

TEST_CASE("SIGKILL: the run file opens with every flushed frame, and --restart ends bit-identical") {
  const auto reference_dir = scratch("kill_reference");
  REQUIRE(run_shard(quoted_args().substr(1), reference_dir).exit_code == 0);
  const Checkpoint reference = read_checkpoint(reference_dir / "run.checkpoint.h5");

  const auto dir = scratch("killed");
  const pid_t pid = start_shard(dir);
  wait_for_checkpoints(dir, pid);
  kill(pid, SIGKILL);
  CHECK(wait_exit(pid) == 128 + SIGKILL);

  // The checkpoint on disk follows a flushed frame: the run file holds at least that many.
  const Checkpoint at_kill = read_checkpoint(dir / "run.checkpoint.h5");
  REQUIRE(at_kill.simulation.step < reference.simulation.step);
  {
    const RunFile killed(dir / "run.h5");
    const auto frames_flushed = static_cast<std::size_t>(at_kill.number("frames_written"));
    CHECK(killed.frame_count() >= frames_flushed);
    for (std::size_t k = 0; k < killed.frame_count(); ++k) CHECK(killed.read_frame(k).position.size() > 0);
    CHECK(killed.metadata().scene_text.find("plate") != std::string::npos);
  }

  const Outcome resumed = run_shard("run --restart run.h5 --threads 1 --quiet", dir);
  CAPTURE(resumed.err);
  REQUIRE(resumed.exit_code == 0);
  require_identical(read_checkpoint(dir / "run.checkpoint.h5").simulation, reference.simulation);
  CHECK(RunFile(dir / "run.h5").frame_count() == RunFile(reference_dir / "run.h5").frame_count());
}

TEST_CASE("SIGINT and SIGTERM: exit 128 + signal after a checkpoint, and the restart completes the same run") {
  // SIGTERM is what mpirun sends every rank when it is interrupted, and what a batch scheduler
  // sends at a job's time limit: it must stop as cleanly as Ctrl-C.
  const auto reference_dir = scratch("int_reference");
  REQUIRE(run_shard(quoted_args().substr(1), reference_dir).exit_code == 0);
  const Checkpoint reference = read_checkpoint(reference_dir / "run.checkpoint.h5");

  for (const auto& [signal, name] : {std::pair{SIGINT, "SIGINT"}, std::pair{SIGTERM, "SIGTERM"}}) {
    CAPTURE(name);
    const auto dir = scratch(std::string("interrupted_") + name);
    const pid_t pid = start_shard(dir);
    wait_for_checkpoints(dir, pid);
    kill(pid, signal);
    CHECK(wait_exit(pid) == 128 + signal);
    const std::string err = read_text(dir / "stderr.txt");
    CHECK(err.find("error") == std::string::npos);
    const Checkpoint at_interrupt = read_checkpoint(dir / "run.checkpoint.h5");
    CHECK(at_interrupt.simulation.step < reference.simulation.step);
    // The interrupted file is complete: its last frame is the state at the interruption.
    const RunFile interrupted(dir / "run.h5");
    CHECK(interrupted.read_frame(interrupted.frame_count() - 1).step == at_interrupt.simulation.step);

    const Outcome resumed = run_shard("run --restart run.h5 --threads 1 --quiet", dir);
    REQUIRE(resumed.exit_code == 0);
    require_identical(read_checkpoint(dir / "run.checkpoint.h5").simulation, reference.simulation);
  }
}
