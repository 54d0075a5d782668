#include "shard/driver/parallel_runs.hpp"

#include <algorithm>
#include <atomic>
#include <exception>
#include <mutex>
#include <thread>

#include "shard/output.hpp"

namespace shard::driver {

std::vector<std::string> run_in_parallel(std::size_t count, int workers, const std::function<void(std::size_t)>& run,
                                         const std::function<void(std::size_t, const std::string&)>& done) {
  std::vector<std::string> errors(count);
  std::atomic<std::size_t> next{0};
  std::mutex report;
  auto worker = [&] {
    for (std::size_t i = next++; i < count; i = next++) {
      std::string error;
      try {
        run(i);
      } catch (const std::exception& e) {
        error = e.what();
        if (error.empty()) error = "the run failed without a message";
      } catch (...) {
        error = "the run threw something that is no std::exception";
      }
      const std::lock_guard lock(report);
      errors[i] = error;
      if (done) {
        try {
          done(i, error);
        } catch (const std::exception& e) {
          // The report of a finished run failed (its cache file, say): the run counts as failed.
          if (errors[i].empty()) errors[i] = e.what();
        }
      }
    }
  };
  const std::size_t threads = std::clamp<std::size_t>(static_cast<std::size_t>(std::max(1, workers)), 1,
                                                      std::max<std::size_t>(1, count));
  std::vector<std::thread> pool;
  // Only new threads run: a run sets its thread's OpenMP team size, which must not stick to the caller's.
  for (std::size_t t = 0; t < threads; ++t) pool.emplace_back(worker);
  for (auto& t : pool) t.join();
  return errors;
}

int in_process_workers(int workers, std::size_t count) {
  return workers > 1 && count > 1 && !run_files_thread_safe() ? 1 : workers;
}

}  // namespace shard::driver
