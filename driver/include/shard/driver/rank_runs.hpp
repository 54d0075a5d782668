#pragma once
// Independent runs spread over MPI ranks (only in a build with -DSHARD_WITH_MPI=ON, which defines
// SHARD_MPI_ENSEMBLE): rank 0 runs the command and hands the runs out, one at a time, to the
// other ranks, which run them and send back what they produced; a rank that finishes gets the
// next one (master/worker over MPI messages). Jobs and results are opaque byte records here
// (the measurement loop's are in apps/src/run_job.hpp). MPI is called from the main thread only.
#include <cstddef>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

namespace shard::driver {

// MPI for the life of this object: initialised here unless something else already did (then
// left to it); on rank 0 the destructor releases the worker ranks (they return from serve()),
// then MPI is finalised if it was initialised here.
class RankEnsemble {
 public:
  RankEnsemble(int& argc, char**& argv);
  ~RankEnsemble();
  RankEnsemble(const RankEnsemble&) = delete;
  RankEnsemble& operator=(const RankEnsemble&) = delete;

  int rank() const { return rank_; }
  int size() const { return size_; }
  // On a rank other than 0: receives jobs from rank 0, answers each with run(job), until rank 0
  // releases the ranks. run must not throw (a failed run is a result like any other). Returns 0.
  int serve(const std::function<std::string(std::string_view)>& run) const;

 private:
  int rank_ = 0, size_ = 1;
  bool initialised_here_ = false;
};

// True on rank 0 of more than one rank while a RankEnsemble is alive: run_on_ranks has workers.
bool ranks_available();
// The ranks that run jobs: every rank but 0.
int worker_rank_count();

// Rank 0: sends job(i) for each i in [0, count) to a free worker rank and calls done(i, result)
// with what it answered, in the order the results arrive, until every job is answered. Returns
// the message of each job whose job() or done() threw (empty: none), by index.
std::vector<std::string> run_on_ranks(std::size_t count, const std::function<std::string(std::size_t)>& job,
                                      const std::function<void(std::size_t, const std::string&)>& done);

}  // namespace shard::driver
