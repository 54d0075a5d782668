#pragma once
// A law written once for any lane type T: T = double is one bond (the scalar reference, width 1),
// T = xsimd::batch<double, A> is one bond per SIMD lane (shard/lanes/xsimd_lanes.hpp). The law
// calls the operations below unqualified after `using namespace shard::lanes`: for double these
// overloads are found, for an xsimd batch argument-dependent lookup finds xsimd's of the same
// name. Each rounds as the IEEE operation it names, so a law without fused multiply-adds gives
// the same bits at every width.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>

namespace shard::lanes {

// What a lane type brings besides arithmetic: its mask and index types, width, loads and stores.
template <class T>
struct Lanes;

template <>
struct Lanes<double> {
  using mask = bool;
  using index = std::int64_t;
  static constexpr std::size_t width = 1;
  [[gnu::always_inline]] static double gather(const double* base, index i) { return base[i]; }
  [[gnu::always_inline]] static void scatter(double* base, index i, double v) { base[i] = v; }
  [[gnu::always_inline]] static double load(const double* p) { return *p; }
  [[gnu::always_inline]] static void store(double* p, double v) { *p = v; }
  [[gnu::always_inline]] static index load_index(const std::int64_t* p) { return *p; }
  [[gnu::always_inline]] static double broadcast(double v) { return v; }
  [[gnu::always_inline]] static bool lane(bool m, std::size_t) { return m; }
};

inline double select(bool m, double a, double b) { return m ? a : b; }
inline bool any(bool m) { return m; }
inline double sqrt(double x) { return std::sqrt(x); }
inline double abs(double x) { return std::abs(x); }
inline double min(double a, double b) { return std::min(a, b); }
inline double max(double a, double b) { return std::max(a, b); }
inline double copysign(double a, double b) { return std::copysign(a, b); }

}  // namespace shard::lanes
