#include "shard/mpi/init.hpp"

#include <mpi.h>

#include <cstdlib>

namespace shard::mpi {

void init_funneled(int* argc, char*** argv) {
  // Open MPI reads its MCA parameters from the environment at initialisation; the last argument 0
  // keeps a value the user set.
  setenv("OMPI_MCA_sharedfp", "^sm", 0);
  int provided = 0;
  MPI_Init_thread(argc, argv, MPI_THREAD_FUNNELED, &provided);
}

}  // namespace shard::mpi
