// A run killed with SIGKILL (no destructor, no atexit, no HDF5 close) must leave a file that
// opens and holds, bit for bit, every frame it had flushed, plus the series and events written
// before it. The kill lands at varying moments of the following writes (series blocks, frame
// datasets, flushes) so each trial interrupts a different operation.
#include <doctest/doctest.h>
#include <hdf5.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>

#include "run_fixtures.hpp"
#include "shard/run_file.hpp"

using namespace shard;
using namespace shard::test;

namespace {

constexpr std::size_t kParticles = 3000;
constexpr std::int64_t kRowsPerFrame = 100;  // more than a 64-row block between frames
constexpr std::int64_t kEventsPerFrame = 40;
constexpr int kFramesBeforeKill = 4;
// A dozen trials in the suite; SHARD_KILL_TRIALS=1000 for a soak run.
int trial_count() {
  const char* text = std::getenv("SHARD_KILL_TRIALS");
  return text != nullptr ? std::max(1, std::atoi(text)) : 12;
}

// The child: writes frames until killed, reporting each finished frame on `report`.
[[noreturn]] void write_until_killed(const std::filesystem::path& path, int report) {
  ::prctl(PR_SET_PDEATHSIG, SIGKILL);  // never outlive a crashed test
  try {
    RunWriter writer(path, make_metadata(), {"pin", "support"});
    std::int64_t row = 0, event = 0;
    for (int frame = 0; frame < 100000; ++frame) {
      for (std::int64_t r = 0; r < kRowsPerFrame; ++r) writer.append_series(make_row(row++, 2));
      std::vector<BondBreakEvent> batch;
      for (std::int64_t e = 0; e < kEventsPerFrame; ++e) batch.push_back(make_event(event++));
      writer.append_break_events(batch);
      writer.write_frame(frame, frame * 1e-3, make_particles(kParticles, frame),
                         make_chain(kParticles, static_cast<std::size_t>(frame)));
      const char done = 1;
      if (::write(report, &done, 1) != 1) ::_exit(3);
    }
  } catch (...) {
    ::_exit(2);
  }
  ::_exit(1);
}

void check_file(const std::filesystem::path& path, int frames_reported) {
  const RunFile run(path);
  const std::size_t frames = run.frame_count();
  CHECK(frames >= static_cast<std::size_t>(frames_reported));
  for (std::size_t k = 0; k < frames; ++k) {
    const FrameData f = run.read_frame(k);
    const int frame = static_cast<int>(k);
    const Particles p = make_particles(kParticles, frame);
    CHECK(f.step == frame);
    CHECK(f.time == frame * 1e-3);
    CHECK(f.id == p.id);
    CHECK(f.position == p.position);
    CHECK(f.velocity == p.velocity);
    CHECK(f.omega == p.omega);
    CHECK(f.radius == p.radius);
    CHECK(f.material == p.material);
    CHECK(f.bond_i.size() == kParticles - 2);
  }
  // Every frame flushed the rows and events appended before it.
  const std::size_t rows = run.series_rows();
  CHECK(rows >= frames * kRowsPerFrame);
  const auto time = run.read_series("time");
  const auto force = run.read_wall_series("support", "force");
  REQUIRE(time.size() == rows);
  REQUIRE(force.size() == rows);
  for (std::size_t r = 0; r < rows; ++r) {
    const SeriesRow e = make_row(static_cast<std::int64_t>(r), 2);
    REQUIRE(time[r] == e.time);
    REQUIRE(force[r] == e.wall_force[1]);
  }
  const auto events = run.read_break_events();
  CHECK(events.size() >= frames * kEventsPerFrame);
  for (std::size_t k = 0; k < events.size(); ++k) {
    const BondBreakEvent e = make_event(static_cast<std::int64_t>(k));
    REQUIRE(events[k].stress.sigma_vm == e.stress.sigma_vm);
    REQUIRE(events[k].midpoint == e.midpoint);
  }
  CHECK(run.metadata().scene_text == make_metadata().scene_text);
}

}  // namespace

TEST_CASE("a run killed with SIGKILL keeps every frame flushed before the kill") {
  const int trials = trial_count();
  for (int trial = 0; trial < trials; ++trial) {
    CAPTURE(trial);
    TempFolder folder("kill" + std::to_string(trial));
    const auto path = folder.path() / "run.h5";
    int pipe_fds[2];
    REQUIRE(::pipe(pipe_fds) == 0);
    const pid_t child = ::fork();
    REQUIRE(child >= 0);
    if (child == 0) {
      ::close(pipe_fds[0]);
      write_until_killed(path, pipe_fds[1]);
    }
    ::close(pipe_fds[1]);
    int reported = 0;
    char done = 0;
    while (reported < kFramesBeforeKill && ::read(pipe_fds[0], &done, 1) == 1) ++reported;
    // 0 to ~6 ms more: the next frame takes a few ms, so the kill falls anywhere inside it.
    ::usleep(static_cast<useconds_t>((trial * 523) % 6000));
    ::kill(child, SIGKILL);
    int status = 0;
    ::waitpid(child, &status, 0);
    while (::read(pipe_fds[0], &done, 1) == 1) ++reported;  // frames finished before the kill
    ::close(pipe_fds[0]);
    REQUIRE(WIFSIGNALED(status));  // the child was writing, not failed
    REQUIRE(reported >= kFramesBeforeKill);
    check_file(path, reported);
    // The reader closed every file, group, dataset and attribute it opened, also on a torn file.
    // (Datatypes are left out: the sanitizer build counts HDF5's own 125 from the start.)
    CHECK(H5Fget_obj_count(static_cast<hid_t>(H5F_OBJ_ALL),
                           H5F_OBJ_FILE | H5F_OBJ_GROUP | H5F_OBJ_DATASET | H5F_OBJ_ATTR) == 0);
  }
}
