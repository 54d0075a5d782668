// Eight lanes' rows of doubles into one vector per component (docs/explanation/performance.md): the
// gather instruction per component against the row loads and in-register transposition of
// shard/lanes/avx512_rows.hpp that the beam block step uses. Rows of 4 (a Quat) and of 3 (a Vec3)
// from an 18 000-particle array at bond-like indices (sorted, neighbours within ~200 places).
//   bench_rows [repeats=30]
// Prints the best time per 8 lanes of each; both sums must agree (the same values are loaded).
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <vector>

#if defined(__x86_64__)
#include <immintrin.h>

#include "shard/lanes/avx512_rows.hpp"

namespace {

using Clock = std::chrono::steady_clock;

template <std::size_t C>
double sum_of(const __m512d (&v)[C]) {
  __m512d s = v[0];
  for (std::size_t c = 1; c < C; ++c) s = _mm512_add_pd(s, v[c]);
  return _mm512_reduce_add_pd(s);
}

// Best seconds over `repeats` of all groups, and the sum of what was loaded.
template <std::size_t C, bool rows>
double run(const std::vector<double>& data, const std::vector<std::int64_t>& offset, int repeats, double& sum) {
  double best = 1e300;
  for (int r = 0; r < repeats; ++r) {
    double s = 0;
    const auto t0 = Clock::now();
    for (std::size_t g = 0; g + 8 <= offset.size(); g += 8) {
      __m512d v[C];
      if constexpr (rows) {
        if constexpr (C <= 4) shard::lanes::detail::load_rows4<C>(data.data(), offset.data() + g, v);
        else shard::lanes::detail::load_rows8<C>(data.data(), offset.data() + g, v);
      } else {
        const __m512i i = _mm512_loadu_si512(offset.data() + g);
        for (std::size_t c = 0; c < C; ++c) v[c] = _mm512_i64gather_pd(i, data.data() + c, 8);
      }
      s += sum_of(v);
    }
    best = std::min(best, std::chrono::duration<double>(Clock::now() - t0).count());
    sum = s;
  }
  return best;
}

template <std::size_t C>
void compare(int repeats) {
  constexpr std::size_t particles = 18000, lanes = 1 << 16;
  std::vector<double> data(C * particles);
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-1, 1);
  for (double& x : data) x = u(rng);
  std::vector<std::int64_t> offset(lanes);
  for (std::size_t k = 0; k < lanes; ++k)
    offset[k] = static_cast<std::int64_t>(C * ((k / 6 + rng() % 200) % particles));
  double gathered = 0, transposed = 0;
  const double t_gather = run<C, false>(data, offset, repeats, gathered);
  const double t_rows = run<C, true>(data, offset, repeats, transposed);
  const double groups = static_cast<double>(lanes / 8);
  std::printf("bench_rows: components=%zu gather_ns_per_8_lanes=%.2f rows_ns_per_8_lanes=%.2f same_values=%s\n", C,
              1e9 * t_gather / groups, 1e9 * t_rows / groups, gathered == transposed ? "yes" : "NO");
}

}  // namespace

int main(int argc, char** argv) {
  if (!__builtin_cpu_supports("avx512f")) {
    std::printf("bench_rows: this CPU has no AVX-512\n");
    return 0;
  }
  const int repeats = argc > 1 ? std::atoi(argv[1]) : 30;
  compare<4>(repeats);
  compare<3>(repeats);
  compare<8>(repeats);
  return 0;
}
#else
int main() {
  std::printf("bench_rows: x86-64 only\n");
  return 0;
}
#endif
