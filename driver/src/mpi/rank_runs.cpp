#include "shard/driver/rank_runs.hpp"

#include <mpi.h>

#include <fmt/format.h>

#include <chrono>
#include <climits>
#include <exception>
#include <stdexcept>
#include <thread>

#include "shard/mpi/init.hpp"

namespace shard::driver {
namespace {

enum Tag : int { kJob = 1, kResult = 2, kRelease = 3 };

// A waiting rank sleeps between looks at its queue: OpenMPI's blocking receive spins on a core,
// which on a machine where the ranks share cores would take it from the ranks that compute.
// A millisecond is nothing to a run of seconds.
MPI_Status wait_for_message(int source, int tag) {
  for (;;) {
    int arrived = 0;
    MPI_Status status;
    MPI_Iprobe(source, tag, MPI_COMM_WORLD, &arrived, &status);
    if (arrived) return status;
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
}

std::string receive(const MPI_Status& status) {
  int size = 0;
  MPI_Get_count(&status, MPI_BYTE, &size);
  std::string bytes(static_cast<std::size_t>(size), '\0');
  MPI_Recv(bytes.data(), size, MPI_BYTE, status.MPI_SOURCE, status.MPI_TAG, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
  return bytes;
}

void send(const std::string& bytes, int rank, int tag) {
  if (bytes.size() > static_cast<std::size_t>(INT_MAX))
    throw std::runtime_error(fmt::format("a message of {} bytes is larger than one MPI message carries", bytes.size()));
  MPI_Send(bytes.data(), static_cast<int>(bytes.size()), MPI_BYTE, rank, tag, MPI_COMM_WORLD);
}

bool mpi_running() {
  int initialised = 0, finalised = 0;
  MPI_Initialized(&initialised);
  MPI_Finalized(&finalised);
  return initialised && !finalised;
}

}  // namespace

RankEnsemble::RankEnsemble(int& argc, char**& argv) {
  if (!mpi_running()) {
    mpi::init_funneled(&argc, &argv);
    initialised_here_ = true;
  }
  MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
  MPI_Comm_size(MPI_COMM_WORLD, &size_);
}

RankEnsemble::~RankEnsemble() {
  if (!mpi_running()) return;
  if (rank_ == 0)
    for (int r = 1; r < size_; ++r) MPI_Send(nullptr, 0, MPI_BYTE, r, kRelease, MPI_COMM_WORLD);
  if (initialised_here_) MPI_Finalize();
}

int RankEnsemble::serve(const std::function<std::string(std::string_view)>& run) const {
  for (;;) {
    const MPI_Status status = wait_for_message(0, MPI_ANY_TAG);
    const std::string job = receive(status);
    if (status.MPI_TAG == kRelease) return 0;
    send(run(job), 0, kResult);
  }
}

bool ranks_available() {
  if (!mpi_running()) return false;
  int rank = 0, size = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  return rank == 0 && size > 1;
}

int worker_rank_count() {
  int size = 1;
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  return size - 1;
}

std::vector<std::string> run_on_ranks(std::size_t count, const std::function<std::string(std::size_t)>& job,
                                      const std::function<void(std::size_t, const std::string&)>& done) {
  int size = 1;
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  std::vector<std::string> errors(count);
  std::vector<std::size_t> job_of(static_cast<std::size_t>(size), count);  // count: the rank is free
  std::size_t next = 0, busy = 0;
  // Gives rank r the next job whose record could be made; false when none is left.
  auto hand_out = [&](int r) {
    while (next < count) {
      const std::size_t i = next++;
      std::string record;
      try {
        record = job(i);
      } catch (const std::exception& e) {
        errors[i] = e.what();
        continue;
      }
      send(record, r, kJob);
      job_of[static_cast<std::size_t>(r)] = i;
      ++busy;
      return true;
    }
    return false;
  };
  for (int r = 1; r < size && hand_out(r);) ++r;
  while (busy > 0) {
    const MPI_Status status = wait_for_message(MPI_ANY_SOURCE, kResult);
    const std::string result = receive(status);
    const int r = status.MPI_SOURCE;
    const std::size_t i = job_of[static_cast<std::size_t>(r)];
    job_of[static_cast<std::size_t>(r)] = count;
    --busy;
    try {
      done(i, result);
    } catch (const std::exception& e) {
      errors[i] = e.what();
    }
    hand_out(r);
  }
  return errors;
}

}  // namespace shard::driver
