// `mpirun -np N shard run`: the run's MPI session and driver::run_distributed, one run of a scene
// over the MPI backend (mpi_backend.cpp).
#include "shard/driver/distributed_run.hpp"

#include <fmt/format.h>
#include <mpi.h>

#include <climits>
#include <cstdio>
#include <cstdlib>
#ifdef __GLIBC__
#include <malloc.h>
#endif

#include "../run_scene.hpp"
#include "mpi_backend.hpp"
#include "shard/mpi/init.hpp"

namespace shard::driver {

bool launched_by_mpi() {
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_SIZE", "PMI_RANK"})
    if (std::getenv(name)) return true;
  return false;
}

MpiSession::MpiSession() {
  int initialised = 0;
  MPI_Initialized(&initialised);
  if (!initialised) {
    mpi::init_funneled(nullptr, nullptr);
    initialised_here_ = true;
  }
  MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
  MPI_Comm_size(MPI_COMM_WORLD, &size_);
}

MpiSession::~MpiSession() {
  int finalised = 0;
  MPI_Finalized(&finalised);
  if (initialised_here_ && !finalised) MPI_Finalize();
}

void abort_job(const std::string& message) {
  int initialised = 0;
  MPI_Initialized(&initialised);
  int rank = 0;
  if (initialised) MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  std::fprintf(stderr, "shard: error%s: %s\n", rank == 0 ? "" : fmt::format(" (rank {})", rank).c_str(),
               message.c_str());
  std::fflush(stderr);
  if (initialised) MPI_Abort(MPI_COMM_WORLD, 1);
  std::exit(1);
}

namespace {

// Every frame and checkpoint allocates and frees the rank's share of the state (tens of MB). By
// default glibc maps each large block anew and hands freed memory at the heap's top back to the
// system, so every checkpoint would fault its pages in again (docs/explanation/performance.md,
// "Set-up of a decomposed run"). A rank holds its peak memory for the whole run anyway, so
// keeping what it frees costs nothing.
void keep_freed_memory() {
#ifdef __GLIBC__
  mallopt(M_MMAP_MAX, 0);
  mallopt(M_TRIM_THRESHOLD, INT_MAX);
#endif
}

}  // namespace

RunResult run_distributed(const RunSpec& spec, const PluginHost& host, const std::vector<RunObserver*>& observers,
                          const RunLog& log) {
  keep_freed_memory();
  detail::MpiBackend backend;
  return detail::run_scene(spec, host, observers, log, backend);
}

}  // namespace shard::driver
