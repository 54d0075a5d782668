#pragma once
// One run of a scene decomposed in space over the MPI ranks of the job (docs/explanation/scaling.md):
// `mpirun -np N shard run SCENE` in a build with -DSHARD_WITH_MPI=ON. It is driver::run's set-up
// and loop over the MPI backend, so every scene feature runs as it does serially. Every rank calls
// run_distributed with the same spec and observers; the observers see the run's step, time, walls
// and load on every rank and the whole run's break counts and frames (RunState::whole), so the
// stop rules decide alike everywhere. Every rank writes its rows of the run file through MPI-IO
// (the serial layout, read by RunFile); rank 0 writes the checkpoints (restart on any rank count,
// or in the serial build) and labels the gathered frames' fragments. This header needs no mpi.h.
#include <string>
#include <vector>

#include "shard/driver/run_driver.hpp"

namespace shard::driver {

// True when this process was started by an MPI launcher (mpirun, srun: it finds their variables).
bool launched_by_mpi();

// MPI for the life of this object: initialised here unless something else already did (then left
// to it), finalised here if initialised here.
class MpiSession {
 public:
  MpiSession();
  ~MpiSession();
  MpiSession(const MpiSession&) = delete;
  MpiSession& operator=(const MpiSession&) = delete;
  int rank() const { return rank_; }
  int size() const { return size_; }

 private:
  int rank_ = 0, size_ = 1;
  bool initialised_here_ = false;
};

// Collective over MPI_COMM_WORLD. Throws as driver::run does; an error met on every rank alike
// (the scene, the checkpoint, the rank count, rank 0's output folder and file) is thrown on every
// rank with the same message.
RunResult run_distributed(const RunSpec& spec, const PluginHost& host, const std::vector<RunObserver*>& observers,
                          const RunLog& log = {});

// For an error one rank met alone (the others would wait for it forever): prints `message` with
// the rank's number, then ends every rank of the job (MPI_Abort) with exit status 1.
[[noreturn]] void abort_job(const std::string& message);

}  // namespace shard::driver
