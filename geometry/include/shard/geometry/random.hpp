#pragma once
// Reproducible random numbers for packings: std::mt19937_64's sequence is fixed by the C++
// standard, but the standard distributions are not, so the conversion to [0,1) is done here.
// Same seed -> same packing bit for bit on every conforming library.
#include <cmath>
#include <cstdint>
#include <random>

#include "shard/types.hpp"

namespace shard::geometry {

class Random {
 public:
  explicit Random(std::uint64_t seed) : engine_(seed) {}
  // Uniform in [0, 1) with 53 random bits.
  double uniform() { return static_cast<double>(engine_() >> 11) * 0x1.0p-53; }
  double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }
  // Uniform direction on the unit sphere (Archimedes: z uniform, azimuth uniform).
  Vec3 direction() {
    const double z = uniform(-1.0, 1.0);
    const double phi = uniform(0.0, 2.0 * 3.14159265358979323846);
    const double s = std::sqrt(std::max(0.0, 1.0 - z * z));
    return {s * std::cos(phi), s * std::sin(phi), z};
  }

 private:
  std::mt19937_64 engine_;
};

}  // namespace shard::geometry
