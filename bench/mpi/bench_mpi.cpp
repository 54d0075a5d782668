// The decomposed step loop (docs/explanation/scaling.md, "Measured speed-up" and "Cost model"). Modes:
//   mpirun -np N bench_mpi [--barriers] [--serial] [block] [particles=20000] [steps=300] [pull_speed=0.2]
//       bench_kernel's bonded block on N ranks
//   mpirun -np N bench_mpi [--barriers] [--serial] pack [particles=100000] [steps=100]
//       bench_kernel's dense unbonded Hertz-Mindlin pack (contacts only: the per-particle cost)
//   mpirun -np N bench_mpi [--barriers] [--serial] scene FILE [steps=50] [section.key=value ...]
//       a scene file through the kernel's scene loader and generator plugins (the seed beam)
//   bench_mpi partition block N P1 P2 ... | partition scene FILE P1 P2 ...
//       the decomposition's partition on P ranks computed in one process: owned, ghosts, neighbours
//   mpirun -np N bench_mpi frames [particles=20000] [reps=20]
//       a frame gathered to rank 0 (the old and the lean gather) and written by the serial writer
//   mpirun -np 2 bench_mpi pingpong
//       point-to-point latency and bandwidth between two ranks (the halo's message cost)
// --serial: the serial Simulation of the same problem on one rank, threads from OMP_NUM_THREADS (the
// OpenMP comparison on the same binary). --barriers: a barrier before each exchange and the
// per-step reduction, timed apart, so the exchange time is the transfer without the waiting for
// the slowest rank. Rank 0 prints one summary line, then one line per rank; times are wall
// (MPI_Wtime) unless named cpu (getrusage: user + system of the whole process, OpenMP threads and
// MPI's polling included; repartition_cpu_ms: the rank's thread alone, per re-partition, with
// `migrated` the particles it sent per re-partition). The one-line commands of the figures: bench/mpi/measure.sh.
#include <fmt/format.h>
#include <hdf5.h>
#include <mpi.h>
#include <omp.h>
#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "../kernel/bench_scenes.hpp"
#include "partition_report.hpp"
#include "scene_setup.hpp"
#include "shard/mpi/distributed_simulation.hpp"
#include "shard/mpi/init.hpp"
#include "shard/output.hpp"

using namespace shard;

namespace {

double cpu_seconds() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  const auto s = [](const timeval& t) { return static_cast<double>(t.tv_sec) + 1e-6 * static_cast<double>(t.tv_usec); };
  return s(u.ru_utime) + s(u.ru_stime);
}

// The one-minute load average: every figure states the load it was taken at.
double load1() {
  std::ifstream f("/proc/loadavg");
  double l = -1;
  f >> l;
  return l;
}

struct Options {
  bool barriers = false, serial = false;
  std::vector<std::string> args;  // the rest, mode first
};

Options parse(int argc, char** argv) {
  Options o;
  for (int k = 1; k < argc; ++k) {
    const std::string a = argv[k];
    if (a == "--barriers") o.barriers = true;
    else if (a == "--serial") o.serial = true;
    else o.args.push_back(a);
  }
  // The first form of the benchmark: `bench_mpi 20000 300`.
  if (o.args.empty() || (o.args[0] != "scene" && o.args[0] != "partition" && o.args[0] != "pingpong" && o.args[0] != "block" && o.args[0] != "frames" &&
                          o.args[0] != "pack"))
    o.args.insert(o.args.begin(), "block");
  return o;
}

std::string arg(const std::vector<std::string>& a, std::size_t k, const std::string& fallback) {
  return a.size() > k ? a[k] : fallback;
}

// One rank's figures of a timed run, per step: means over the run, and the fastest and median
// step (on a shared machine the fastest step is the one both ranks ran without waiting for a
// core: the nearest to an idle figure a loaded machine gives).
struct RankFigures {
  double pid, owned, ghosts, neighbours, cpu_ms, pack_ms, exchange_ms, unpack_ms, barrier_ms, reduction_ms, partition_ms,
      compute_ms;
  // Per re-partition in the timed steps: this rank's CPU time in it, the particles it sent.
  double repartition_cpu_ms, migrated;
  double step_min_ms, step_median_ms, compute_min_ms, compute_median_ms, halo_min_ms, halo_median_ms, reduction_min_ms;
};

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0 : v[v.size() / 2];
}

double smallest(const std::vector<double>& v) { return v.empty() ? 0 : *std::min_element(v.begin(), v.end()); }

void timed_distributed(const char* label, mpi::DistributedSimulation& sim, long steps, long warmup, bool barriers,
                       double setup_seconds) {
  sim.set_timing_barriers(barriers);
  sim.run(warmup);  // buffers sized, first exchanges made
  const auto p0 = sim.phase_seconds();
  const long repartitions0 = sim.repartitions();
  const std::size_t migrated0 = sim.migration_total().particles;
  const double load_before = load1();
  const auto n = static_cast<std::size_t>(steps);
  std::vector<double> step_ms(n), compute_ms(n), halo_ms(n), reduction_ms(n);
  MPI_Barrier(MPI_COMM_WORLD);
  const double start = MPI_Wtime(), cpu_start = cpu_seconds();
  for (std::size_t s = 0; s < n; ++s) {
    const auto a = sim.phase_seconds();
    const double t = MPI_Wtime();
    sim.step();
    const double wall = MPI_Wtime() - t;
    const auto b = sim.phase_seconds();
    const double halo = (b.pack - a.pack) + (b.exchange - a.exchange) + (b.unpack - a.unpack);
    const double other = (b.barrier - a.barrier) + (b.reduction - a.reduction) + (b.partition - a.partition);
    step_ms[s] = 1e3 * wall;
    halo_ms[s] = 1e3 * halo;
    reduction_ms[s] = 1e3 * (b.reduction - a.reduction);
    compute_ms[s] = 1e3 * (wall - halo - other);
  }
  const double cpu = cpu_seconds() - cpu_start;
  const double mine = MPI_Wtime() - start;  // this rank's wall time, before waiting for the others
  MPI_Barrier(MPI_COMM_WORLD);
  const double seconds = MPI_Wtime() - start;
  const auto p1 = sim.phase_seconds();
  const double per = 1e3 / static_cast<double>(steps);
  RankFigures f{};
  f.pid = static_cast<double>(getpid());  // names the rank's callgrind file (callgrind_split.sh)
  f.owned = static_cast<double>(sim.owned());
  f.ghosts = static_cast<double>(sim.ghosts());
  f.neighbours = static_cast<double>(sim.halo_neighbours());
  f.cpu_ms = per * cpu;
  f.pack_ms = per * (p1.pack - p0.pack);
  f.exchange_ms = per * (p1.exchange - p0.exchange);
  f.unpack_ms = per * (p1.unpack - p0.unpack);
  f.barrier_ms = per * (p1.barrier - p0.barrier);
  f.reduction_ms = per * (p1.reduction - p0.reduction);
  f.partition_ms = per * (p1.partition - p0.partition);
  const double cuts = std::max(1.0, static_cast<double>(sim.repartitions() - repartitions0));
  f.repartition_cpu_ms = 1e3 * (p1.repartition_cpu - p0.repartition_cpu) / cuts;
  f.migrated = static_cast<double>(sim.migration_total().particles - migrated0) / cuts;
  f.compute_ms = per * mine - (f.pack_ms + f.exchange_ms + f.unpack_ms + f.barrier_ms + f.reduction_ms + f.partition_ms);
  f.step_min_ms = smallest(step_ms);
  f.step_median_ms = median(step_ms);
  f.compute_min_ms = smallest(compute_ms);
  f.compute_median_ms = median(compute_ms);
  f.halo_min_ms = smallest(halo_ms);
  f.halo_median_ms = median(halo_ms);
  f.reduction_min_ms = smallest(reduction_ms);
  std::vector<RankFigures> all(static_cast<std::size_t>(sim.ranks()));
  MPI_Gather(&f, sizeof f, MPI_BYTE, all.data(), sizeof f, MPI_BYTE, 0, MPI_COMM_WORLD);
  const std::size_t bonds = sim.bond_count();
  const std::size_t contacts = sim.contact_count();
  if (sim.rank() != 0) return;
  RankFigures m{};  // largest over the ranks
  double ghosts = 0, halo_share = 0;
  std::size_t particles = 0;
  for (const RankFigures& r : all) {
    particles += static_cast<std::size_t>(r.owned);
    ghosts += r.ghosts;
    m.cpu_ms = std::max(m.cpu_ms, r.cpu_ms);
    m.compute_ms = std::max(m.compute_ms, r.compute_ms);
    m.pack_ms = std::max(m.pack_ms, r.pack_ms);
    m.exchange_ms = std::max(m.exchange_ms, r.exchange_ms);
    m.unpack_ms = std::max(m.unpack_ms, r.unpack_ms);
    m.barrier_ms = std::max(m.barrier_ms, r.barrier_ms);
    m.reduction_ms = std::max(m.reduction_ms, r.reduction_ms);
    m.partition_ms = std::max(m.partition_ms, r.partition_ms);
    m.repartition_cpu_ms = std::max(m.repartition_cpu_ms, r.repartition_cpu_ms);
    m.migrated = std::max(m.migrated, r.migrated);
    m.step_min_ms = std::max(m.step_min_ms, r.step_min_ms);
    m.step_median_ms = std::max(m.step_median_ms, r.step_median_ms);
    m.compute_min_ms = std::max(m.compute_min_ms, r.compute_min_ms);
    m.compute_median_ms = std::max(m.compute_median_ms, r.compute_median_ms);
    m.halo_min_ms = std::max(m.halo_min_ms, r.halo_min_ms);
    m.halo_median_ms = std::max(m.halo_median_ms, r.halo_median_ms);
    m.reduction_min_ms = std::max(m.reduction_min_ms, r.reduction_min_ms);
    halo_share = std::max(halo_share, (r.pack_ms + r.exchange_ms + r.unpack_ms) / (per * seconds));
  }
  std::printf("bench_mpi %s ranks=%d threads=%d barriers=%d particles=%zu bonds=%zu contacts=%zu ghosts=%.0f steps=%ld "
              "load_before=%.2f load_after=%.2f setup_s=%.1f ms_per_step=%.3f cpu_ms_per_step_max_rank=%.3f "
              "compute_ms_max=%.3f pack_ms_max=%.4f exchange_ms_max=%.4f unpack_ms_max=%.4f barrier_ms_max=%.4f "
              "reduction_ms_max=%.4f partition_ms_max=%.4f halo_share=%.3f repartitions=%ld step_min_ms=%.3f "
              "step_median_ms=%.3f compute_min_ms=%.3f compute_median_ms=%.3f halo_min_ms=%.4f halo_median_ms=%.4f "
              "reduction_min_ms=%.4f repartition_cpu_ms_max=%.3f migrated_max=%.0f\n",
              label, sim.ranks(), omp_get_max_threads(), barriers ? 1 : 0, particles, bonds, contacts, ghosts, steps,
              load_before, load1(), setup_seconds, per * seconds, m.cpu_ms, m.compute_ms, m.pack_ms, m.exchange_ms,
              m.unpack_ms, m.barrier_ms, m.reduction_ms, m.partition_ms, halo_share,
              static_cast<long>(sim.repartitions() - repartitions0), m.step_min_ms, m.step_median_ms, m.compute_min_ms,
              m.compute_median_ms, m.halo_min_ms, m.halo_median_ms, m.reduction_min_ms, m.repartition_cpu_ms, m.migrated);
  for (std::size_t r = 0; r < all.size(); ++r) {
    const RankFigures& x = all[r];
    std::printf("bench_mpi_rank %s rank=%zu pid=%.0f owned=%.0f ghosts=%.0f neighbours=%.0f cpu_ms=%.3f compute_ms=%.3f pack_ms=%.4f "
                "exchange_ms=%.4f unpack_ms=%.4f barrier_ms=%.4f reduction_ms=%.4f partition_ms=%.4f step_min_ms=%.3f "
                "compute_min_ms=%.3f halo_min_ms=%.4f repartition_cpu_ms=%.3f migrated=%.0f\n",
                label, r, x.pid, x.owned, x.ghosts, x.neighbours, x.cpu_ms, x.compute_ms, x.pack_ms, x.exchange_ms, x.unpack_ms,
                x.barrier_ms, x.reduction_ms, x.partition_ms, x.step_min_ms, x.compute_min_ms, x.halo_min_ms,
                x.repartition_cpu_ms, x.migrated);
  }
  std::fflush(stdout);
}

// The serial Simulation on this process's OpenMP team, measured alike (one rank only).
void timed_serial(const char* label, Simulation& sim, long steps, long warmup, double setup_seconds) {
  sim.run(warmup);
  const double load_before = load1();
  std::vector<double> step_ms(static_cast<std::size_t>(steps));
  const double start = MPI_Wtime(), cpu_start = cpu_seconds();
  for (double& ms : step_ms) {
    const double t = MPI_Wtime();
    sim.step();
    ms = 1e3 * (MPI_Wtime() - t);
  }
  const double cpu = cpu_seconds() - cpu_start, seconds = MPI_Wtime() - start;
  const double per = 1e3 / static_cast<double>(steps);
  std::printf("bench_mpi %s serial threads=%d particles=%zu bonds=%zu contacts=%zu steps=%ld load_before=%.2f load_after=%.2f "
              "setup_s=%.1f ms_per_step=%.3f cpu_ms_per_step=%.3f step_min_ms=%.3f step_median_ms=%.3f rebuilds=%lld\n",
              label, omp_get_max_threads(), sim.particles().size(), sim.bonds().size(), sim.contact_count(), steps,
              load_before, load1(), setup_seconds, per * seconds, per * cpu, smallest(step_ms), median(step_ms),
              static_cast<long long>(sim.neighbour_rebuilds()));
  std::fflush(stdout);
}

int block(const Options& o, int ranks) {
  const std::size_t target = std::stoul(arg(o.args, 1, "20000"));
  const long steps = std::stol(arg(o.args, 2, "300"));
  const double speed = std::stod(arg(o.args, 3, "0.2"));
  const double t0 = MPI_Wtime();
  const bench::Models models = bench::default_models();
  if (o.serial) {
    if (ranks != 1) throw std::invalid_argument("--serial runs on one rank");
    Simulation sim(bench::bonded_block(target, speed, models));
    timed_serial("bonded", sim, steps, 5, MPI_Wtime() - t0);
    return 0;
  }
  mpi::DistributedSimulation sim(MPI_COMM_WORLD, bench::bonded_block(target, speed, models));
  timed_distributed("bonded", sim, steps, 5, o.barriers, MPI_Wtime() - t0);
  return 0;
}

int pack(const Options& o, int ranks) {
  const std::size_t target = std::stoul(arg(o.args, 1, "100000"));
  const long steps = std::stol(arg(o.args, 2, "100"));
  const double t0 = MPI_Wtime();
  const bench::Models models = bench::default_models();
  if (o.serial) {
    if (ranks != 1) throw std::invalid_argument("--serial runs on one rank");
    Simulation sim(bench::dense_pack(target, models));
    timed_serial("pack", sim, steps, 5, MPI_Wtime() - t0);
    return 0;
  }
  mpi::DistributedSimulation sim(MPI_COMM_WORLD, bench::dense_pack(target, models));
  timed_distributed("pack", sim, steps, 5, o.barriers, MPI_Wtime() - t0);
  return 0;
}

int scene(const Options& o, int ranks) {
  if (o.args.size() < 2) throw std::invalid_argument("bench_mpi scene FILE [steps=50] [section.key=value ...]");
  const long steps = std::stol(arg(o.args, 2, "50"));
  const std::vector<std::string> overrides(o.args.begin() + std::min<std::ptrdiff_t>(3, static_cast<std::ptrdiff_t>(o.args.size())),
                                           o.args.end());
  const double t0 = MPI_Wtime();
  bench::LoadedScene loaded(o.args[1], overrides);
  if (o.serial) {
    if (ranks != 1) throw std::invalid_argument("--serial runs on one rank");
    timed_serial("scene", *loaded.instance.simulation, steps, 2, MPI_Wtime() - t0);
    return 0;
  }
  SimulationSetup setup = loaded.setup();
  loaded.instance.simulation.reset();  // the serial copy is not stepped: free its memory
  mpi::DistributedSimulation sim(MPI_COMM_WORLD, std::move(setup));
  timed_distributed("scene", sim, steps, 2, o.barriers, MPI_Wtime() - t0);
  return 0;
}

int partition(const Options& o, int rank) {
  if (o.args.size() < 4) throw std::invalid_argument("bench_mpi partition block N P... | partition scene FILE P...");
  std::vector<int> counts;
  for (std::size_t k = 3; k < o.args.size(); ++k) counts.push_back(std::stoi(o.args[k]));
  if (rank != 0) return 0;
  if (o.args[1] == "block") {
    const bench::Models models = bench::default_models();
    const std::string label = "block" + o.args[2];
    bench::print_partitions(label.c_str(), bench::bonded_block(std::stoul(o.args[2]), 0.2, models), counts, stdout);
  } else {
    const bench::LoadedScene loaded(o.args[2], {});
    bench::print_partitions(std::filesystem::path(o.args[2]).stem().c_str(), loaded.setup(), counts, stdout);
  }
  return 0;
}

// What a frame of `shard run` decomposed costs (docs/explanation/scaling.md, "How the world is cut"): the bonded block
// stepped a little, then `reps` gathers of a frame to rank 0 the way the run driver did before
// session 9 (gather_state without contacts: whole particle records, bonds with model state) and
// the way a labelled frame is gathered now (gather_frame: a frame's fields, bonds as id pairs),
// rank 0 writing the gathered frame through the serial RunWriter (flushed at each frame, as in a
// run), and the parallel frame the driver writes: each rank's share (frame_share) written by all
// ranks at once into a file opened through MPI-IO (write_frame_part), plus for a labelled frame
// the gather of ids, masses and bond rows to rank 0. Medians of wall (MPI_Wtime) and of rank 0's CPU
// time per call (and the largest rank's CPU for the parallel write).
int frames(const Options& o, int rank) {
  const std::size_t target = std::stoul(arg(o.args, 1, "20000"));
  const int reps = std::stoi(arg(o.args, 2, "20"));
  const bench::Models models = bench::default_models();
  mpi::DistributedSimulation sim(MPI_COMM_WORLD, bench::bonded_block(target, 0.2, models));
  sim.run(10);
  const auto timed = [&](auto&& call) {
    std::vector<double> wall, cpu;
    for (int k = 0; k < reps; ++k) {
      MPI_Barrier(MPI_COMM_WORLD);
      const double t = MPI_Wtime(), c = cpu_seconds();
      call();
      cpu.push_back(cpu_seconds() - c);
      wall.push_back(MPI_Wtime() - t);
    }
    return std::pair{1e3 * median(wall), 1e3 * median(cpu)};
  };
  std::size_t particles = 0, bonds = 0, stride = 0;
  const auto whole = timed([&] {
    const SimulationState s = sim.gather_state(0, false);
    particles = s.particles.size();
    bonds = s.bonds.size();
    stride = s.bonds.stride;
  });
  const auto lean = timed([&] { (void)sim.gather_frame(0); });
  std::pair<double, double> write{0, 0};
  long long pid = getpid();  // rank 0's: the file every rank shares below
  MPI_Bcast(&pid, 1, MPI_LONG_LONG, 0, MPI_COMM_WORLD);
  const std::filesystem::path file = std::filesystem::temp_directory_path() / fmt::format("bench_mpi_frames_{}.h5", pid);
  const std::filesystem::path shared = std::filesystem::temp_directory_path() / fmt::format("bench_mpi_parallel_{}.h5", pid);
  // Parallel: every rank's own rows at once through MPI-IO (the driver's frames without labels).
  const auto share = timed([&] { (void)sim.frame_share(); });
  // What a labelled frame gathers on top of its share: ids, masses and bond rows to rank 0.
  const mpi::FrameShare one = sim.frame_share();
  const auto label_gather = timed([&] {
    (void)sim.gather_to_root(one.particles.id);
    (void)sim.gather_to_root(one.particles.mass);
    (void)sim.gather_to_root(one.bond_rows);
  });
  std::pair<double, double> parallel{0, 0};
  double parallel_cpu_max = 0;
  {
    RunWriterAccess access;
    access.configure = [](std::int64_t list) { H5Pset_fapl_mpio(list, MPI_COMM_WORLD, MPI_INFO_NULL); };
    access.writes_index = rank == 0;
    RunWriter writer(shared, RunMetadata{}, {}, access);
    int k = 0;
    parallel = timed([&] {
      const mpi::FrameShare f = sim.frame_share();
      FramePart part;
      part.particles = &f.particles;
      part.first_row = f.first_row;
      part.total_rows = f.total_rows;
      part.bond_rows = &f.bond_rows;
      part.first_bond = f.first_bond;
      part.total_bonds = f.total_bonds;
      part.configure_transfer = [](std::int64_t list) { H5Pset_dxpl_mpio(list, H5FD_MPIO_COLLECTIVE); };
      writer.write_frame_part(k++, 0.0, part);
    });
    MPI_Reduce(&parallel.second, &parallel_cpu_max, 1, MPI_DOUBLE, MPI_MAX, 0, MPI_COMM_WORLD);
  }
  const mpi::GatheredFrame f = sim.gather_frame(0);  // collective: every rank takes part
  if (rank == 0) {
    RunMetadata meta;
    RunWriter writer(file, meta, {});
    std::vector<double> wall, cpu;
    for (int k = 0; k < reps; ++k) {
      const double t = MPI_Wtime(), c = cpu_seconds();
      writer.write_frame(k, 0.0, f.particles, f.bonds);
      cpu.push_back(cpu_seconds() - c);
      wall.push_back(MPI_Wtime() - t);
    }
    write = {1e3 * median(wall), 1e3 * median(cpu)};
  }
  if (rank == 0) {
    for (std::filesystem::path written : {file, shared}) {
      std::filesystem::remove(written);
      std::filesystem::remove(written.replace_extension(".xmf"));
    }
    int ranks = 1;
    MPI_Comm_size(MPI_COMM_WORLD, &ranks);
    std::printf("frames ranks=%d particles=%zu bonds=%zu bond_stride=%zu reps=%d load=%.2f "
                "gather_state_ms=%.3f gather_state_cpu_ms=%.3f gather_frame_ms=%.3f gather_frame_cpu_ms=%.3f "
                "write_frame_ms=%.3f write_frame_cpu_ms=%.3f frame_share_ms=%.3f frame_share_cpu_ms=%.3f "
                "label_gather_ms=%.3f label_gather_cpu_ms=%.3f "
                "parallel_write_ms=%.3f parallel_write_cpu_ms=%.3f parallel_write_cpu_max_ms=%.3f\n",
                ranks, particles, bonds, stride, reps, load1(), whole.first, whole.second, lean.first, lean.second,
                write.first, write.second, share.first, share.second, label_gather.first, label_gather.second,
                parallel.first, parallel.second, parallel_cpu_max);
  }
  return 0;
}

// Half the round trip of a message of n bytes between ranks 0 and 1, best and median of many.
int pingpong(int rank, int ranks) {
  if (ranks != 2) throw std::invalid_argument("pingpong runs on exactly 2 ranks");
  for (const std::size_t bytes : {8ul, 512ul, 4096ul, 32768ul, 262144ul, 1048576ul, 4194304ul}) {
    std::vector<char> buffer(bytes);
    const int reps = bytes > 100000 ? 50 : 500;
    std::vector<double> times;
    for (int k = 0; k < reps; ++k) {
      MPI_Barrier(MPI_COMM_WORLD);
      const double t = MPI_Wtime();
      if (rank == 0) {
        MPI_Send(buffer.data(), static_cast<int>(bytes), MPI_BYTE, 1, 5, MPI_COMM_WORLD);
        MPI_Recv(buffer.data(), static_cast<int>(bytes), MPI_BYTE, 1, 5, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
      } else {
        MPI_Recv(buffer.data(), static_cast<int>(bytes), MPI_BYTE, 0, 5, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
        MPI_Send(buffer.data(), static_cast<int>(bytes), MPI_BYTE, 0, 5, MPI_COMM_WORLD);
      }
      times.push_back(0.5 * (MPI_Wtime() - t));
    }
    std::sort(times.begin(), times.end());
    if (rank == 0)
      std::printf("pingpong bytes=%zu reps=%d load=%.2f best_us=%.2f median_us=%.2f best_MB_per_s=%.1f\n", bytes, reps, load1(),
                  1e6 * times.front(), 1e6 * times[times.size() / 2], 1e-6 * static_cast<double>(bytes) / times.front());
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  shard::mpi::init_funneled(&argc, &argv);
  int rank = 0, ranks = 1, code = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &ranks);
  try {
    const Options o = parse(argc, argv);
    if (o.args[0] == "block") code = block(o, ranks);
    else if (o.args[0] == "pack") code = pack(o, ranks);
    else if (o.args[0] == "scene") code = scene(o, ranks);
    else if (o.args[0] == "partition") code = partition(o, rank);
    else if (o.args[0] == "frames") code = frames(o, rank);
    else code = pingpong(rank, ranks);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_mpi (rank %d): %s\n", rank, e.what());
    MPI_Abort(MPI_COMM_WORLD, 1);
  }
  MPI_Finalize();
  return code;
}
