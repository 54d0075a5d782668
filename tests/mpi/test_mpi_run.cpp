// `shard run` decomposed over MPI ranks (driver::run_distributed) against the serial driver, on
// scenes/four_point_bending_ci.toml made short: damping off (as test_mpi_beam: Cundall's damping
// amplifies round-off), pins at 0.1 m/s and a bond strength of 0.05 MPa, so the first bonds break
// after ~500 steps and the load-drop rule ends the run ~200 steps later. Fragment labels in every
// frame. Modes (the run files are read back with the serial RunFile reader):
//   serial OUT               the reference: driver::run, no MPI
//   decomposed OUT REF       mpirun -np N: the same run decomposed (fragment labels in every frame:
//                            by the distributed union-find, written by every rank); rank 0 compares OUT with REF:
//                            up to the first break, the load curve and every frame's positions
//                            within 1e-9 of the displacement scale (the pins' travel at the first
//                            break); over the whole run the same breaks (step, ids) in order, the
//                            same stop step, the same ids, bonds (as id pairs) and fragment labels
//                            in every frame
//   parallel_frames OUT REF  as `decomposed` without fragment labels: every rank writes its own
//                            particles and bonds of each frame (parallel HDF5); compared alike, and
//                            bit for bit with the same run labelled
//   interrupt OUT STEP       mpirun -np N: the run stopped at STEP (checkpoint written)
//   restart OUT REF          mpirun -np M: continues OUT (written on another rank count) to its end
//                            and compares with REF as `decomposed` does
//   no_ids DIR REF           mpirun -np N: a copy of REF whose checkpoint lacks /particles/id is
//                            refused on every rank with a CheckpointError naming the fix
//   kill OUT REF MPIRUN EXE  (no mpirun) starts `MPIRUN -np 2 EXE checkpointing OUT`, a run that
//                            checkpoints at every frame (every rank writing its share), and kills
//                            both ranks with SIGKILL while a checkpoint is being written (its
//                            temporary file exists, the previous one beside it), three times at
//                            later checkpoints; the previous
//                            checkpoint must then read, and `MPIRUN -np 2 EXE restart OUT REF`
//                            continue it to the reference's end
//   bad_generator OUT        mpirun -np N: the generator's box too small for one sphere: its
//                            failure on rank 0 (which alone generates) is a SceneError on every
//                            rank, naming the scene file, line and section
//   checkpointing OUT        mpirun -np N: the run with a checkpoint at every frame, each rank's
//                            pid in OUT/pid.RANK
//   stale_semaphores OUT REF mpirun -np N: as `parallel_frames`, beside taken POSIX semaphores
//                            named as Open MPI's shared-file-pointer component names those of
//                            the run's files (what a job killed with the file open leaves); the
//                            run must not wait on them (shard::mpi::init_funneled)
// Exit code 0 on success; each check prints one line on rank 0.
#include <fmt/format.h>
#include <hdf5.h>
#include <mpi.h>
#include <fcntl.h>
#include <semaphore.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <thread>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "shard/checkpoint.hpp"
#include "shard/driver/checkpoint_writer.hpp"
#include "shard/driver/distributed_run.hpp"
#include "shard/driver/run_driver.hpp"
#include "shard/driver/scene_rules.hpp"
#include "shard/driver/stop_rules.hpp"
#include "shard/plugin_host.hpp"
#include "shard/run_file.hpp"

using namespace shard;
namespace fs = std::filesystem;

namespace {

int failures = 0;
int rank_ = 0;
void check(bool ok, const std::string& what) {
  if (!ok) ++failures;
  if (rank_ == 0) std::printf("%s: %s\n", ok ? "ok  " : "FAIL", what.c_str());
}

driver::RunSpec spec_for(const fs::path& out) {
  driver::RunSpec spec;
  spec.scene = fs::path(SHARD_SOURCE_DIR) / "scenes" / "four_point_bending_ci.toml";
  spec.overrides = parse_overrides({"simulation.global_damping=0", "wall.pin_left.velocity=[0,0,-0.1]",
                                    "wall.pin_right.velocity=[0,0,-0.1]", "bond.critical_stress=0.05e6",
                                    "simulation.duration=0.02", "output.frame_interval=0.0005",
                                    "output.series_interval=0.0001", "analysis.fragments_every=1"});
  spec.out_dir = out;
  spec.threads = 1;
  return spec;
}

void load_plugins(PluginHost& host) { host.load_directories({fs::path(SHARD_BUILD_DIR) / "plugins"}); }

// The run's observers as `shard run` composes them (less the printing ones).
struct Observers {
  driver::SceneRules rules;
  driver::CheckpointWriter checkpoints;
  driver::InterruptStop interrupt;
  explicit Observers(std::int64_t at_step = -1, int checkpoint_every = 0)
      : checkpoints(checkpoint_every), interrupt(at_step) {}
  std::vector<driver::RunObserver*> list() {
    auto l = rules.observers();
    l.insert(l.end(), {&checkpoints, &interrupt});
    return l;
  }
};

// The load on the pins (the scene's load sensor: -z force of both) per series row.
std::vector<double> pin_load(const RunFile& f) {
  const auto l = f.read_wall_series("pin_left", "force"), r = f.read_wall_series("pin_right", "force");
  std::vector<double> out;
  for (std::size_t k = 0; k < l.size(); ++k) out.push_back(-(l[k].z() + r[k].z()));
  return out;
}

std::map<Index, std::size_t> rows_by_id(const FrameData& f) {
  std::map<Index, std::size_t> m;
  for (std::size_t k = 0; k < f.id.size(); ++k) m[f.id[k]] = k;
  return m;
}

// A frame's bonds as (smaller id, larger id) pairs, sorted: what the rows mean whatever the order.
std::vector<std::pair<Index, Index>> bond_ids(const FrameData& f) {
  std::vector<std::pair<Index, Index>> out;
  for (std::size_t k = 0; k < f.bond_i.size(); ++k) {
    const Index a = f.id[static_cast<std::size_t>(f.bond_i[k])], b = f.id[static_cast<std::size_t>(f.bond_j[k])];
    out.emplace_back(std::min(a, b), std::max(a, b));
  }
  std::sort(out.begin(), out.end());
  return out;
}

// What a decomposed run file must share with the serial one (see the header); `labelled`: its
// frames carry fragment labels (written gathered) or none (written by every rank in parallel).
void compare(const fs::path& file, const fs::path& reference, const std::string& who, bool labelled = true) {
  const RunFile a(file), b(reference);
  const auto ea = a.read_break_events(), eb = b.read_break_events();
  check(!eb.empty(), "the reference run breaks bonds");
  if (eb.empty()) return;
  const std::int64_t first_break = eb.front().step;
  bool same_breaks = ea.size() == eb.size();
  for (std::size_t k = 0; same_breaks && k < ea.size(); ++k)
    same_breaks = ea[k].step == eb[k].step && ea[k].id_i == eb[k].id_i && ea[k].id_j == eb[k].id_j;
  if (rank_ == 0) std::printf("%s: %zu breaks (reference %zu), the first at step %lld\n", who.c_str(), ea.size(), eb.size(),
                              static_cast<long long>(first_break));
  check(same_breaks, who + ": the same bonds break at the same steps in the same order");

  const auto sa = a.read_integer_series("step"), sb = b.read_integer_series("step");
  check(sa == sb, who + ": the same series rows (steps), the run stops at the same step");
  const auto da = a.read_wall_series("pin_left", "displacement"), db = b.read_wall_series("pin_left", "displacement");
  const auto la = pin_load(a), lb = pin_load(b);
  double scale = 0, peak = 0, worst_d = 0, worst_l = 0;
  for (std::size_t k = 0; k < std::min(sa.size(), sb.size()) && sb[k] <= first_break; ++k) {
    scale = std::max(scale, std::abs(db[k].z()));
    peak = std::max(peak, std::abs(lb[k]));
    worst_d = std::max(worst_d, (da[k] - db[k]).norm());
    worst_l = std::max(worst_l, std::abs(la[k] - lb[k]));
  }
  if (rank_ == 0)
    std::printf("%s up to the first break: pin travel %.3g m, |d displacement| %.3g m, peak load %.4g N, |d load| %.3g N\n",
                who.c_str(), scale, worst_d, peak, worst_l);
  check(scale > 0 && peak > 0, who + ": the pins move and carry load before the first break");
  check(worst_d <= 1e-9 * scale && worst_l <= 1e-9 * peak,
        who + ": the load curve agrees within 1e-9 of the displacement and load scales up to the first break");

  check(a.frame_count() == b.frame_count(), who + ": the same number of frames");
  double worst_x = 0, worst_after = 0;
  bool same_ids = true, same_labels = true, same_bonds = true;
  for (std::size_t k = 0; k < std::min(a.frame_count(), b.frame_count()); ++k) {
    const FrameData fa = a.read_frame(a.frames()[k]), fb = b.read_frame(b.frames()[k]);
    const auto ra = rows_by_id(fa);
    std::vector<Index> ia = fa.id, ib = fb.id;
    std::sort(ia.begin(), ia.end());
    std::sort(ib.begin(), ib.end());
    same_ids = same_ids && ia == ib && fa.step == fb.step;
    same_bonds = same_bonds && fa.bond_i.size() == fb.bond_i.size() && bond_ids(fa) == bond_ids(fb);
    same_labels = same_labels && (labelled ? fa.fragment && fb.fragment : !fa.fragment);
    if (ia != ib) continue;
    for (std::size_t q = 0; q < fb.id.size(); ++q) {
      const std::size_t p = ra.at(fb.id[q]);
      const double dx = (fa.position[p] - fb.position[q]).norm();
      double& worst = fb.step <= first_break ? worst_x : worst_after;
      worst = std::max(worst, dx);
      if (fa.fragment && fb.fragment) same_labels = same_labels && (*fa.fragment)[p] == (*fb.fragment)[q];
    }
  }
  if (rank_ == 0)
    std::printf("%s frames: max |dx| %.3g m up to the first break (%.3g of the pin travel), %.3g m after it\n",
                who.c_str(), worst_x, worst_x / std::max(scale, 1e-300), worst_after);
  check(same_ids, who + ": every frame holds the same steps and particle ids");
  check(same_bonds, who + ": every frame holds the same bonds (as id pairs)");
  check(worst_x <= 1e-9 * scale, who + ": positions agree within 1e-9 of the pin travel up to the first break");
  check(same_labels, labelled ? who + ": every particle's fragment label is the same in every frame"
                               : who + ": no frame carries fragment labels");
}

// Two files of the same decomposed run (the same rank count: bit-reproducible), one without
// fragment labels and one with (labelled by the distributed union-find): every frame holds the same numbers for every particle id, bit for bit, and the
// same bonds as id pairs; the labels are the only difference.
void compare_bitwise(const fs::path& parallel, const fs::path& gathered, const std::string& who) {
  const RunFile a(parallel), b(gathered);
  bool same = a.frame_count() == b.frame_count() && a.frame_count() > 0;
  bool reordered = false;
  for (std::size_t k = 0; same && k < a.frame_count(); ++k) {
    const FrameData fa = a.read_frame(a.frames()[k]), fb = b.read_frame(b.frames()[k]);
    same = fa.step == fb.step && fa.id.size() == fb.id.size() && bond_ids(fa) == bond_ids(fb);
    reordered = reordered || fa.id != fb.id;
    const auto ra = rows_by_id(fa);
    for (std::size_t q = 0; same && q < fb.id.size(); ++q) {
      const auto it = ra.find(fb.id[q]);
      if (it == ra.end()) {
        same = false;
        break;
      }
      const std::size_t p = it->second;
      same = fa.position[p] == fb.position[q] && fa.velocity[p] == fb.velocity[q] && fa.omega[p] == fb.omega[q] &&
             fa.radius[p] == fb.radius[q] && fa.mass[p] == fb.mass[q] && fa.material[p] == fb.material[q] &&
             fa.body[p] == fb.body[q];
    }
  }
  check(same && !reordered, who + ": with labels or without, every frame holds bit for bit the same particles (in "
                                "the same rows) and bonds");
}

int run_decomposed(const driver::RunSpec& spec, Observers& o) {
  PluginHost host;
  load_plugins(host);
  driver::run_distributed(spec, host, o.list());
  return 0;
}


// Runs `args` (argv[0] the program) in a child process of its own process group; returns its pid.
pid_t spawn(const std::vector<std::string>& args) {
  const pid_t child = ::fork();
  if (child != 0) return child;
  ::setpgid(0, 0);
  std::vector<char*> argv;
  for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  ::execv(argv[0], argv.data());
  ::_exit(127);
}

int exit_code(pid_t child) {
  int status = 0;
  ::waitpid(child, &status, 0);
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

// The ranks' pids, once both have written them.
std::vector<pid_t> rank_pids(const fs::path& out, int ranks) {
  std::vector<pid_t> pids;
  for (int r = 0; r < ranks; ++r) {
    std::ifstream in(out / fmt::format("pid.{}", r));
    long pid = 0;
    if (in >> pid) pids.push_back(static_cast<pid_t>(pid));
  }
  return pids;
}

// Waits (polling every 50 us, at most 60 s) until the `nth` checkpoint write seen (its temporary
// file appearing) is under way over an earlier one, then kills the ranks `delay_us` later.
// Returns whether it caught one.
bool kill_during_checkpoint(const fs::path& out, int nth, int delay_us) {
  const fs::path done = out / "run.checkpoint.h5", partial = out / "run.checkpoint.h5.tmp";
  int seen = 0;
  bool writing = false;
  for (int k = 0; k < 1200000; ++k) {
    const bool now = fs::exists(partial);
    if (now && !writing) ++seen;
    writing = now;
    const std::vector<pid_t> pids = rank_pids(out, 2);
    if (writing && seen >= nth && pids.size() == 2 && fs::exists(done)) {
      if (delay_us > 0) ::usleep(static_cast<useconds_t>(delay_us));
      for (pid_t p : pids) ::kill(p, SIGKILL);
      return true;
    }
    ::usleep(50);
  }
  return false;
}

int kill_and_continue(const fs::path& out, const fs::path& reference, const std::string& mpirun, const std::string& exe) {
  const std::vector<std::string> launch = {mpirun, "--allow-run-as-root", "--oversubscribe", "-np", "2", exe};
  // Three kills, in the 2nd, 6th and 10th checkpoint write seen, at 0, 0.5 and 1 ms into it, each
  // followed by the restart to the end.
  for (int trial = 0; trial < 3; ++trial) {
    fs::remove_all(out);
    fs::create_directories(out);
    std::vector<std::string> run = launch;
    run.insert(run.end(), {"checkpointing", out.string()});
    const pid_t job = spawn(run);
    const bool caught = kill_during_checkpoint(out, 2 + 4 * trial, 500 * trial);
    if (!caught) ::kill(-job, SIGKILL);
    const int code = exit_code(job);
    ::kill(-job, SIGKILL);  // whatever of mpirun's group is left
    check(caught, fmt::format("trial {}: both ranks killed while a checkpoint was being written (mpirun exit {})",
                              trial, code));
    if (!caught) continue;
    std::int64_t step = -1;
    try {
      step = read_checkpoint(out / "run.checkpoint.h5").simulation.step;
    } catch (const std::exception& e) {
      std::printf("%s\n", e.what());
    }
    std::printf("trial %d: the previous checkpoint holds step %lld; a torn temporary file is %s\n", trial,
                static_cast<long long>(step), fs::exists(out / "run.checkpoint.h5.tmp") ? "beside it" : "gone");
    check(step >= 0, fmt::format("trial {}: the previous checkpoint reads", trial));
    std::vector<std::string> again = launch;
    again.insert(again.end(), {"restart", out.string(), reference.string()});
    check(exit_code(spawn(again)) == 0,
          fmt::format("trial {}: 2 ranks continue it to the reference's end (its checks above)", trial));
  }
  return failures > 0 ? 1 : 0;
}

// Taken semaphores under the names a job killed while writing this run's files leaves in
// /dev/shm, removed again when the holder goes (by every rank: a second removal finds none).
class StaleFileSemaphores {
 public:
  StaleFileSemaphores() {
    for (const char* file : {"run.h5", "run.checkpoint.h5", "run.checkpoint.h5.tmp"}) {
      const std::string name = std::string("/OMPIO_") + file;
      sem_t* taken = sem_open(name.c_str(), O_CREAT, 0644, 0);
      check(taken != SEM_FAILED, "a taken semaphore " + name + " made");
      if (taken != SEM_FAILED) sem_close(taken);
      names_.push_back(name);
    }
  }
  ~StaleFileSemaphores() {
    for (const std::string& name : names_) sem_unlink(name.c_str());
  }
  StaleFileSemaphores(const StaleFileSemaphores&) = delete;
  StaleFileSemaphores& operator=(const StaleFileSemaphores&) = delete;

 private:
  std::vector<std::string> names_;
};

}  // namespace

int main(int argc, char** argv) {
  H5dont_atexit();
  if (argc < 3) {
    std::fprintf(stderr, "usage: test_mpi_run serial|decomposed|parallel_frames|interrupt|restart|no_ids|kill|checkpointing|stale_semaphores ARGS\n");
    return 2;
  }
  const std::string mode = argv[1];
  const fs::path out = argv[2];
  if (mode == "serial") {
    PluginHost host;
    load_plugins(host);
    Observers o;
    fs::remove_all(out);
    const driver::RunResult r = driver::run(spec_for(out), host, o.list());
    std::printf("serial: %lld steps, %lld bonds broken, %s\n", static_cast<long long>(r.steps),
                static_cast<long long>(r.bonds_broken), r.stop_reason.c_str());
    return r.bonds_broken > 0 ? 0 : 1;
  }
  if (mode == "serial_restart" && argc > 4) {
    // The serial driver continues a decomposed run's checkpoint (the checkpoint is gathered in the
    // serial layout): a copy of the interrupted 4-rank run, to its end.
    fs::remove_all(out);
    fs::create_directories(out);
    for (const char* name : {"run.h5", "run.checkpoint.h5"}) fs::copy_file(fs::path(argv[3]) / name, out / name);
    PluginHost host;
    load_plugins(host);
    Observers o;
    driver::RunSpec spec = spec_for(out);
    spec.restart = out / "run.h5";
    driver::run(spec, host, o.list());
    compare(out / "run.h5", fs::path(argv[4]) / "run.h5", "serial build continuing 4 ranks");
    return failures > 0 ? 1 : 0;
  }
  if (mode == "kill" && argc > 5) return kill_and_continue(out, argv[3], argv[4], argv[5]);
  const bool beside_stale_semaphores = mode == "stale_semaphores";
  const std::optional<StaleFileSemaphores> stale = beside_stale_semaphores ? std::make_optional<StaleFileSemaphores>() : std::nullopt;
  const driver::MpiSession mpi;
  rank_ = mpi.rank();
  const std::string who = fmt::format("{} ranks", mpi.size());
  try {
    if ((mode == "decomposed" || mode == "parallel_frames" || beside_stale_semaphores) && argc > 3) {
      // parallel_frames: no fragment labels.
      const bool labelled = mode == "decomposed";
      if (rank_ == 0) fs::remove_all(out);
      MPI_Barrier(MPI_COMM_WORLD);
      Observers o;
      driver::RunSpec spec = spec_for(out);
      if (!labelled)
        for (auto& extra : parse_overrides({"analysis.fragments_every=0"})) spec.overrides.push_back(extra);
      const double t0 = MPI_Wtime();
      run_decomposed(spec, o);
      if (rank_ == 0) std::printf("%s: the run took %.2f s\n", who.c_str(), MPI_Wtime() - t0);
      if (rank_ == 0) compare(out / "run.h5", fs::path(argv[3]) / "run.h5", who, labelled);
      if (!labelled && !beside_stale_semaphores) {
        // The same run with labels: labelling must change nothing else in the file.
        Observers again;
        run_decomposed(spec_for(out / "gathered"), again);
        if (rank_ == 0) compare_bitwise(out / "run.h5", out / "gathered" / "run.h5", who);
      }
    } else if (mode == "interrupt" && argc > 3) {
      if (rank_ == 0) fs::remove_all(out);
      MPI_Barrier(MPI_COMM_WORLD);
      Observers o(std::stoll(argv[3]));
      run_decomposed(spec_for(out), o);
      if (rank_ == 0) {
        const Checkpoint c = read_checkpoint(out / "run.checkpoint.h5");
        check(c.simulation.step == std::stoll(argv[3]), fmt::format("{}: the checkpoint holds step {}", who, argv[3]));
        check(c.simulation.particles.size() == 582, who + ": the checkpoint holds every particle");
        // A copy for the serial build to continue (test_mpi_run_serial_restart): the 2-rank restart
        // continues this folder in place.
        const fs::path copy = out.parent_path() / "restart_copy";
        fs::remove_all(copy);
        fs::create_directories(copy);
        for (const char* name : {"run.h5", "run.checkpoint.h5"}) fs::copy_file(out / name, copy / name);
      }
    } else if (mode == "bad_generator") {
      Observers o;
      driver::RunSpec spec = spec_for(out);
      for (auto& extra : parse_overrides({"generator.max_corner=[-0.0899,-0.0149,0.0001]"})) spec.overrides.push_back(extra);
      std::string message;
      try {
        run_decomposed(spec, o);
      } catch (const SceneError& e) {
        message = e.what();
      }
      std::printf("rank %d: %s\n", rank_, message.c_str());
      const bool named = message.find("four_point_bending_ci.toml:25:1: [generator] box_fill: the box") != std::string::npos;
      int mine = named ? 1 : 0, all = 0;
      MPI_Allreduce(&mine, &all, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD);
      check(all, who + ": every rank refuses the scene whose generator failed on rank 0, naming file, line and section");
    } else if (mode == "checkpointing") {
      std::ofstream(out / fmt::format("pid.{}", rank_)) << ::getpid() << std::endl;
      Observers o(-1, 1);
      run_decomposed(spec_for(out), o);
    } else if (mode == "restart" && argc > 3) {
      Observers o;
      driver::RunSpec spec = spec_for(out);
      spec.restart = out / "run.h5";
      run_decomposed(spec, o);
      if (rank_ == 0) compare(out / "run.h5", fs::path(argv[3]) / "run.h5", who + " (restarted)");
    } else if (mode == "no_ids" && argc > 3) {
      if (rank_ == 0) {
        fs::remove_all(out);
        fs::create_directories(out);
        fs::copy_file(fs::path(argv[3]) / "run.h5", out / "run.h5");
        fs::copy_file(fs::path(argv[3]) / "run.checkpoint.h5", out / "run.checkpoint.h5");
        const hid_t f = H5Fopen((out / "run.checkpoint.h5").c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
        check(f >= 0 && H5Ldelete(f, "particles/id", H5P_DEFAULT) >= 0, "the copy's /particles/id removed");
        H5Fclose(f);
      }
      MPI_Barrier(MPI_COMM_WORLD);
      Observers o;
      driver::RunSpec spec = spec_for(out);
      spec.restart = out / "run.h5";
      std::string message;
      try {
        run_decomposed(spec, o);
      } catch (const CheckpointError& e) {
        message = e.what();
      }
      std::printf("rank %d: %s\n", rank_, message.c_str());
      const bool named = message.find("no particle ids") != std::string::npos &&
                         message.find("run.checkpoint.h5") != std::string::npos;
      int mine = named ? 1 : 0, all = 0;
      MPI_Allreduce(&mine, &all, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD);
      check(all, who + ": every rank refuses the checkpoint without ids, naming the file and the fix");
    } else {
      std::fprintf(stderr, "unknown mode %s\n", mode.c_str());
      return 2;
    }
  } catch (const std::exception& e) {
    std::printf("rank %d: FAIL: %s\n", rank_, e.what());
    MPI_Abort(MPI_COMM_WORLD, 1);
  }
  int any = failures;
  MPI_Allreduce(&failures, &any, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD);
  return any > 0 ? 1 : 0;
}
