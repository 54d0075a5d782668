#pragma once
// MPI start-up for every Shard program that writes files through MPI-IO (parallel HDF5).
namespace shard::mpi {

// MPI_Init_thread at MPI_THREAD_FUNNELED (only the main thread calls MPI; a rank's OpenMP threads
// never do), after choosing MPI-IO components that cannot hang between jobs. Open MPI's default
// shared-file-pointer component guards each open file with a POSIX semaphore named after the
// file's base name only (/dev/shm/sem.OMPIO_<name>): two jobs writing run.h5 in different folders
// share it, and a job killed while a file is open leaves it taken, so every later open of a file
// of that name waits forever. HDF5 never uses shared file pointers, so that component is
// switched off unless the user's environment already chooses one (OMPI_MCA_sharedfp).
void init_funneled(int* argc, char*** argv);

}  // namespace shard::mpi
