#pragma once
// Static split of [0, n) over the OpenMP threads: each thread gets one contiguous chunk, so a
// batch model is called once per thread and results do not depend on scheduling.
#include <omp.h>

#include <cstddef>

namespace shard {

template <class Body>
void for_each_chunk(std::size_t n, Body&& body) {
  if (n < 2048 || omp_get_max_threads() == 1) {
    if (n > 0) body(std::size_t{0}, n);
    return;
  }
#pragma omp parallel
  {
    const auto t = static_cast<std::size_t>(omp_get_thread_num());
    const auto nt = static_cast<std::size_t>(omp_get_num_threads());
    const std::size_t begin = n * t / nt, end = n * (t + 1) / nt;
    if (end > begin) body(begin, end);
  }
}

}  // namespace shard
