#pragma once
// The SIMD lane type of shard/lanes/lanes.hpp: xsimd::batch<double, A>, one bond (or pair) per
// lane. Include only in a translation unit compiled for the architecture A (its intrinsics need
// the target's flags), which instantiates the law with this type alone.
#include <cstddef>
#include <cstdint>
#include <type_traits>
#include <xsimd/xsimd.hpp>

#include "shard/lanes/lanes.hpp"

namespace shard::lanes {

template <class A>
struct Lanes<xsimd::batch<double, A>> {
  using type = xsimd::batch<double, A>;
  using mask = xsimd::batch_bool<double, A>;
  using index = xsimd::batch<std::int64_t, A>;
  static constexpr std::size_t width = type::size;
  // xsimd 8.1's batch::gather never reaches its AVX-512 or AVX2 kernels (it passes them one
  // template argument too many) and emulates them with a serial chain of 8 masked blends: the
  // gather instructions are called here directly.
  [[gnu::always_inline]] static type gather(const double* base, const index& i) {
#if defined(__AVX512F__)
    if constexpr (std::is_same_v<A, xsimd::avx512f>) return _mm512_i64gather_pd(i, base, 8);
#endif
#if defined(__AVX2__)
    if constexpr (std::is_same_v<A, xsimd::avx2>) return _mm256_i64gather_pd(base, i, 8);
#endif
    return type::gather(base, i);
  }
  // Lanes with equal indices store the value of the last of them.
  [[gnu::always_inline]] static void scatter(double* base, const index& i, const type& v) {
#if defined(__AVX512F__)
    if constexpr (std::is_same_v<A, xsimd::avx512f>) return _mm512_i64scatter_pd(base, i, v, 8);
#endif
    v.scatter(base, i);
  }
  [[gnu::always_inline]] static type load(const double* p) { return type::load_unaligned(p); }
  [[gnu::always_inline]] static void store(double* p, const type& v) { v.store_unaligned(p); }
  [[gnu::always_inline]] static index load_index(const std::int64_t* p) { return index::load_unaligned(p); }
  [[gnu::always_inline]] static type broadcast(double v) { return type(v); }
  [[gnu::always_inline]] static bool lane(const mask& m, std::size_t l) { return m.get(l); }
};

}  // namespace shard::lanes
