#pragma once
// Scalar features of one force-displacement curve of a four-point bending test, each with the
// standard uncertainty that the sensor noise alone gives it.
//
//   stiffness          k, N/m: least-squares slope of F(w) on the rising branch between 10 % and
//                      60 % of F_max (the toe below 10 % is seating of the pins, not the beam)
//   peak_force         F_max, N
//   peak_displacement  w at F_max, m
//   work_to_peak       integral of F dw from the start to the peak, J
//   nonlinearity       1 - F_max / (k (w_peak - w0)), 1: how far the secant to the peak falls below
//                      the elastic line (w0 = toe offset, where that line crosses F = 0); 0 = linear
//   post_peak_work     integral of F dw after the peak, J
#include <array>
#include <optional>
#include <string_view>
#include <vector>

#include "shard/measure/curve.hpp"

namespace shard::measure {

enum class Feature : std::size_t {
  Stiffness,
  PeakForce,
  PeakDisplacement,
  WorkToPeak,
  Nonlinearity,
  PostPeakWork,
  CrackPosition,
  FragmentX50,
  FragmentCount,
};
inline constexpr std::size_t kFeatureCount = 9;
inline constexpr std::size_t kCurveFeatureCount = 6;  // the first six come from the curve itself

std::string_view feature_name(Feature f);
std::string_view feature_unit(Feature f);
Feature feature_at(std::size_t index);

// One value per feature; nullopt when not measured / not available.
struct FeatureValues {
  std::array<std::optional<double>, kFeatureCount> value{};
  std::array<double, kFeatureCount> sensor_uncertainty{};  // standard, from the sensor noise
  std::optional<double>& operator[](Feature f) { return value[static_cast<std::size_t>(f)]; }
  const std::optional<double>& operator[](Feature f) const { return value[static_cast<std::size_t>(f)]; }
};

struct ElasticFit {
  double stiffness = 0;     // N/m
  double toe_offset = 0;    // m, w at which the elastic line reaches F = 0
  double u_stiffness = 0;   // N/m, standard uncertainty from the force noise
};

std::size_t peak_index(const Curve& c);
ElasticFit elastic_fit(const Curve& c);
FeatureValues curve_features(const Curve& c);

// Mass-weighted median size x50 of a fragment set (masses, or size^3 when no masses are given).
double fragment_x50(const std::vector<double>& sizes, const std::vector<double>& masses);

}  // namespace shard::measure
