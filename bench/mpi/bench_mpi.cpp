// The decomposed step loop (docs/scaling-out.md): `mpirun -np N bench_mpi [particles=20000]
// [steps=300] [pull_speed=0.2]` steps bench_kernel's bonded block on N ranks and prints, on rank 0,
// the wall time per step, the largest rank's CPU time per step, and the shares of the wall time
// spent in the halo exchange (waits included) and in re-partitioning (largest over the ranks).
#include <mpi.h>

#include <ctime>
#include <cstdio>
#include <string>

#include "../kernel/bench_scenes.hpp"
#include "shard/mpi/distributed_simulation.hpp"

using namespace shard;

namespace {
// This process's CPU time, s: on a shared, oversubscribed machine the wall time also counts the
// time a rank waits for the core its neighbour holds.
double cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}
}  // namespace

int main(int argc, char** argv) {
  MPI_Init(&argc, &argv);
  {
    const std::size_t target = argc > 1 ? std::stoul(argv[1]) : 20000;
    const long steps = argc > 2 ? std::stol(argv[2]) : 300;
    const double speed = argc > 3 ? std::stod(argv[3]) : 0.2;
    const bench::Models models = bench::default_models();
    mpi::DistributedSimulation sim(MPI_COMM_WORLD, bench::bonded_block(target, speed, models));
    sim.run(5);  // warm-up: buffers sized, first exchanges made
    const double halo0 = sim.halo_seconds(), part0 = sim.partition_seconds();
    MPI_Barrier(MPI_COMM_WORLD);
    const double start = MPI_Wtime(), cpu_start = cpu_seconds();
    sim.run(steps);
    const double cpu = cpu_seconds() - cpu_start;
    MPI_Barrier(MPI_COMM_WORLD);
    const double seconds = MPI_Wtime() - start;
    const double halo = sim.halo_seconds() - halo0, part = sim.partition_seconds() - part0;
    double halo_max = 0, part_max = 0, cpu_max = 0;
    MPI_Reduce(&cpu, &cpu_max, 1, MPI_DOUBLE, MPI_MAX, 0, MPI_COMM_WORLD);
    MPI_Reduce(&halo, &halo_max, 1, MPI_DOUBLE, MPI_MAX, 0, MPI_COMM_WORLD);
    MPI_Reduce(&part, &part_max, 1, MPI_DOUBLE, MPI_MAX, 0, MPI_COMM_WORLD);
    const std::size_t bonds = sim.bond_count();
    unsigned long ghosts = sim.ghosts(), ghosts_total = 0;
    MPI_Reduce(&ghosts, &ghosts_total, 1, MPI_UNSIGNED_LONG, MPI_SUM, 0, MPI_COMM_WORLD);
    if (sim.rank() == 0)
      std::printf("bench_mpi bonded ranks=%d particles=%zu bonds=%zu ghosts=%lu steps=%ld ms_per_step=%.3f "
                  "cpu_ms_per_step_max_rank=%.3f halo_share=%.3f repartition_share=%.3f repartitions=%lld\n",
                  sim.ranks(), target, bonds, ghosts_total, steps, 1e3 * seconds / static_cast<double>(steps),
                  1e3 * cpu_max / static_cast<double>(steps),
                  halo_max / seconds, part_max / seconds, static_cast<long long>(sim.repartitions()));
  }
  MPI_Finalize();
  return 0;
}
