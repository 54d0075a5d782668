#pragma once
// Per-bond strength scatter: sigma_crit of each bond drawn from a two-parameter Weibull law
//   F(s) = 1 - exp(-(s / s0)^m),   mean = s0 Gamma(1 + 1/m),
// with the mean held at the scene's critical_stress, so changing m changes only the scatter.
// The uniform number comes from a hash of (seed, smaller stable id, larger stable id), not from a
// stream: a bond gets the same strength in every run and whatever order the kernel lists it in,
// which gives common random numbers across the runs of one diagnosis.
#include <boost/math/tools/roots.hpp>
#include <cmath>
#include <cstdint>
#include <utility>

namespace shard::beam {

// SplitMix64 finaliser: a bijection of 64-bit words with full avalanche.
inline std::uint64_t mix64(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

// Uniform in the open interval (0, 1), symmetric in the two ids.
inline double bond_uniform(std::uint64_t seed, std::int64_t id_a, std::int64_t id_b) {
  const auto lo = static_cast<std::uint64_t>(std::min(id_a, id_b));
  const auto hi = static_cast<std::uint64_t>(std::max(id_a, id_b));
  const std::uint64_t h = mix64(mix64(mix64(seed) ^ lo) ^ (hi * 0xd1b54a32d192ed03ULL));
  return (static_cast<double>(h >> 11) + 0.5) * 0x1.0p-53;
}

// Scale s0 that gives the Weibull law of modulus m the mean `mean`.
inline double weibull_scale(double mean, double modulus) { return mean / std::tgamma(1 + 1 / modulus); }

inline double weibull_cdf(double s, double scale, double modulus) {
  return s <= 0 ? 0.0 : 1 - std::exp(-std::pow(s / scale, modulus));
}

// Inverse CDF at u in (0, 1).
inline double weibull_quantile(double u, double scale, double modulus) {
  return scale * std::pow(-std::log1p(-u), 1 / modulus);
}

// Coefficient of variation of the law of modulus m, sqrt(Gamma(1 + 2/m) / Gamma(1 + 1/m)^2 - 1):
// 0.523 at m = 2, 0.281 at m = 4, 0.105 at m = 12; pi / (sqrt(6) m) for large m.
inline double weibull_cv(double modulus) {
  const double g1 = std::tgamma(1 + 1 / modulus);
  return std::sqrt(std::tgamma(1 + 2 / modulus) / (g1 * g1) - 1);
}

// The modulus whose law scatters by `cv` (0 < cv <= kMaxStrengthCv). The scatter, not m, is the
// effect's size: it grows from its neutral 0 with the effect, where m runs the other way and
// jumps from "no scatter" at 0 to the widest scatter just above it.
inline constexpr double kMaxStrengthCv = 2.0;  // m = 0.54
inline double weibull_modulus_for_cv(double cv) {
  // cv(m) falls monotonically; bracket in ln m between m = 0.5 (cv 2.24) and past the asymptote.
  auto excess = [cv](double log_m) { return weibull_cv(std::exp(log_m)) - cv; };
  const double hi = std::log(std::max(1e4, 10 / cv));
  boost::math::tools::eps_tolerance<double> tolerance(50);
  std::uintmax_t iterations = 200;
  const auto [a, b] = boost::math::tools::toms748_solve(excess, std::log(0.5), hi, tolerance, iterations);
  return std::exp(0.5 * (a + b));
}

}  // namespace shard::beam
