#pragma once
// The foreign spring bond's hidden effects (test-only): the library effects of docs/reference/effects.md
// in another form, so a diagnosis is tested on an effect it must recognise by its signature, not
// by its code.
//   strength scatter: every critical force and torque of a bond times one Weibull draw with
//     median 1 (beam_bond's weibull_strength policy keeps the mean of one von Mises strength), from a hash of the two
//     stable particle ids (a murmur-style finaliser; beam_bond uses SplitMix64 and a seed).
//   softening: once the undamaged load ratio c (sqrt of the criterion) passes 1 the elastic loads
//     scale by 1 - (c_max - 1) / s until c_max = 1 + s, where the bond breaks: the force falls
//     parabolically in the deformation (beam_bond's softening policy: linear in the von Mises strain).
//   compression stiffening: the normal spring is ratio x k_n while shortened.
//   rate-dependent strength: subcritical damage D grows at c^n / t_0 (Charles' law of stress
//     corrosion; c the load ratio) and the bond fails at D = 1 or c = 1, so under a ramp its
//     strength grows as rate^(1 / (n + 1)) (beam_bond's viscosity: a Maxwell arm, stiffness too).
//   cohesion: a failed bond pulls its particles together with a constant force up to a range
//     (hertz_mindlin's cohesion: a pull proportional to the contact area, only while touching).
#include <algorithm>
#include <cmath>
#include <cstdint>

namespace shard::foreign {

inline std::uint64_t mix_ids(std::uint64_t a, std::uint64_t b, std::uint64_t seed) {
  std::uint64_t h = (std::min(a, b) << 32) ^ std::max(a, b) ^ (seed * 0xD6E8FEB86659FD93ull);
  h ^= h >> 33;
  h *= 0xFF51AFD7ED558CCDull;
  h ^= h >> 33;
  h *= 0xC4CEB9FE1A85EC53ull;
  h ^= h >> 33;
  return h;
}

// The strength factor of the bond between stable ids a and b: 1 when modulus = 0 (no scatter),
// else a Weibull(modulus) draw scaled to median 1.
inline double strength_factor(double modulus, std::uint64_t a, std::uint64_t b, std::uint64_t seed) {
  if (modulus == 0) return 1;
  const double u = (static_cast<double>(mix_ids(a, b, seed) >> 11) + 0.5) * 0x1.0p-53;  // (0, 1)
  return std::pow(-std::log1p(-u) / std::log(2.0), 1 / modulus);
}

// Factor on the elastic loads after the peak load ratio `peak` (>= 0) for softening s > 0; the
// bond is broken when it returns <= 0.
inline double softening_factor(double peak, double softening) {
  return peak <= 1 ? 1.0 : 1 - (peak - 1) / softening;
}

// Rate of subcritical damage at load ratio c (>= 0), 1/s: none when time = 0.
inline double fatigue_rate(double load_ratio, double exponent, double time) {
  return time > 0 ? std::pow(load_ratio, exponent) / time : 0.0;
}

}  // namespace shard::foreign
