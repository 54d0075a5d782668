// How much parallel capacity the machine gives right now: the same compute-only loop (no memory
// traffic, no synchronisation) on one thread, then on every thread of the OpenMP team at once,
// each thread's CPU time and the wall time. On idle cores the team's wall time equals one
// thread's (speed-up = threads); on this shared VM other sessions' processes take a share of
// every core whatever their nice value (the kernel's autogroup scheduling gives each session a
// fair share), and the speed-up drops towards 1. Run it before a two-thread benchmark: a speed-up
// below ~1.9 here means the benchmark's own cannot show more (docs/explanation/performance.md).
//
//   OMP_NUM_THREADS=2 OMP_WAIT_POLICY=passive taskset -c 0,1 bench_cores [iterations=4e8]
#include <omp.h>

#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <vector>

namespace {

double thread_cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

// A dependent multiply-add chain: latency-bound, the same on any core.
double chain(long iterations) {
  double x = 1.0;
  for (long k = 0; k < iterations; ++k) x = x * 1.0000000001 + 1e-12;
  return x;
}

}  // namespace

int main(int argc, char** argv) {
  const long iterations = argc > 1 ? static_cast<long>(std::atof(argv[1])) : 400000000L;
  const int team = omp_get_max_threads();
  double sink = 0;
  const double w0 = omp_get_wtime();
  sink += chain(iterations);
  const double alone = omp_get_wtime() - w0;
  std::vector<double> cpu(static_cast<std::size_t>(team));
  const double w1 = omp_get_wtime();
#pragma omp parallel num_threads(team) reduction(+ : sink)
  {
    const double c0 = thread_cpu_seconds();
    sink += chain(iterations);
    cpu[static_cast<std::size_t>(omp_get_thread_num())] = thread_cpu_seconds() - c0;
  }
  const double together = omp_get_wtime() - w1;
  std::printf("bench_cores: threads=%d one_thread_wall_s=%.3f team_wall_s=%.3f", team, alone, together);
  for (int t = 0; t < team; ++t) std::printf(" cpu_s[%d]=%.3f", t, cpu[static_cast<std::size_t>(t)]);
  std::printf(" parallel_capacity=%.2f (%g)\n", team * alone / together, sink);
}
