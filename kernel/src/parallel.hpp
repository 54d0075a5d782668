#pragma once
// Static work split over the OpenMP team. Every thread owns one contiguous range, so which
// thread computes what, and the order of every floating-point sum, depend only on the problem
// and the thread count: runs are bit-reproducible for a given OMP_NUM_THREADS.
#include <omp.h>

#include <algorithm>
#include <cstddef>

namespace shard {

struct Range {
  std::size_t begin = 0, end = 0;
};

// Thread t's share of [0, n) when nt threads split it.
inline Range range_of(std::size_t n, int t, int nt) {
  const auto tt = static_cast<std::size_t>(t), nn = static_cast<std::size_t>(nt);
  return {n * tt / nn, n * (tt + 1) / nn};
}

// Below this much work a parallel region costs more than it saves (measured: a region start and
// a barrier are ~1-5 us, one pair or bond ~20-300 ns).
inline constexpr std::size_t kParallelMinWork = 4096;

inline int team_for(std::size_t work) {
  return work < kParallelMinWork ? 1 : std::max(1, omp_get_max_threads());
}

}  // namespace shard
