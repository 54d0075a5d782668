#include "shard/wall_motion.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace shard {
namespace {

// theta - sin(theta), accurate also where the two nearly cancel (small theta): the Taylor series
// below 1 (terms fall by theta^2 / ((2k+2)(2k+3)); 12 terms reach 1e-30 of the first at theta = 1).
double theta_minus_sin(double theta) {
  if (theta >= 1.0) return theta - std::sin(theta);
  const double t2 = theta * theta;
  double term = theta * t2 / 6.0, sum = 0.0;
  for (int k = 1; k <= 12; ++k) {
    sum += term;
    term *= -t2 / static_cast<double>((2 * k + 2) * (2 * k + 3));
  }
  return sum;
}

// The ramp's share of the full speed reached at time t (speed / full speed) and the distance
// travelled per unit of full speed (displacement / full speed, s).
void ramp_profile(WallRamp ramp, double T, double t, double& fraction, double& travel_time) {
  if (ramp == WallRamp::None || t >= T) {
    fraction = 1.0;
    travel_time = ramp == WallRamp::None ? t : t - 0.5 * T;  // both ramps travel T/2 at full speed less
    return;
  }
  if (ramp == WallRamp::Linear) {
    fraction = t / T;
    travel_time = 0.5 * t * t / T;
    return;
  }
  const double theta = std::numbers::pi * t / T;
  const double s = std::sin(0.5 * theta);
  fraction = s * s;  // (1 - cos theta) / 2 without the cancellation at small theta
  travel_time = 0.5 * (T / std::numbers::pi) * theta_minus_sin(theta);
}

// Index k of the table segment [time[k], time[k+1]] holding t (the last one beyond the end).
std::size_t segment(const WallTable& table, double t) {
  const auto it = std::upper_bound(table.time.begin(), table.time.end(), t);
  const std::size_t after = static_cast<std::size_t>(it - table.time.begin());
  return std::min(after == 0 ? 0 : after - 1, table.time.size() - 2);
}

double table_travel(const WallTable& table, double t) {
  const std::size_t k = segment(table, t);
  const double dt = t - table.time[k], span = table.time[k + 1] - table.time[k];
  if (!table.gives_velocity) {
    const double slope = (table.value[k + 1] - table.value[k]) / span;
    return table.travel[k] + slope * dt;
  }
  if (t > table.time.back()) return table.travel.back() + table.value.back() * (t - table.time.back());
  const double accel = (table.value[k + 1] - table.value[k]) / span;
  return table.travel[k] + table.value[k] * dt + 0.5 * accel * dt * dt;
}

double table_speed(const WallTable& table, double t) {
  const std::size_t k = segment(table, t);
  const double span = table.time[k + 1] - table.time[k];
  if (!table.gives_velocity) return (table.value[k + 1] - table.value[k]) / span;
  if (t > table.time.back()) return table.value.back();
  return table.value[k] + (table.value[k + 1] - table.value[k]) * (t - table.time[k]) / span;
}

}  // namespace

bool parse_wall_ramp(const std::string& text, WallRamp& ramp) {
  if (text == "none") ramp = WallRamp::None;
  else if (text == "1-cos") ramp = WallRamp::OneMinusCos;
  else if (text == "linear") ramp = WallRamp::Linear;
  else return false;
  return true;
}

const char* ramp_name(WallRamp ramp) {
  switch (ramp) {
    case WallRamp::None: return "none";
    case WallRamp::OneMinusCos: return "1-cos";
    case WallRamp::Linear: return "linear";
  }
  return "none";
}

void prepare_wall_table(WallTable& table) {
  const std::size_t n = table.time.size();
  if (n < 2 || table.value.size() != n)
    throw std::invalid_argument(fmt::format("{}: a motion table needs at least two rows of time and {}", table.file,
                                            table.gives_velocity ? "velocity" : "displacement"));
  if (table.time[0] != 0.0)
    throw std::invalid_argument(fmt::format("{}: the motion table's first time is {} s; it must start at 0 (the start "
                                            "of the run)",
                                            table.file, table.time[0]));
  for (std::size_t k = 1; k < n; ++k)
    if (!(table.time[k] > table.time[k - 1]))
      throw std::invalid_argument(fmt::format("{}: data row {} (time {} s) is not later than the row before it ({} s); the "
                                              "times must increase strictly",
                                              table.file, k + 1, table.time[k], table.time[k - 1]));
  table.travel.assign(n, 0.0);
  for (std::size_t k = 1; k < n; ++k)
    table.travel[k] = table.gives_velocity
                          ? table.travel[k - 1] + 0.5 * (table.value[k] + table.value[k - 1]) *
                                                      (table.time[k] - table.time[k - 1])
                          : table.value[k] - table.value[0];
}

Vec3 WallMotion::displacement_at(double t) const {
  if (t <= start_time) return Vec3::Zero();
  t -= start_time;
  if (!table.time.empty()) return table_travel(table, t) * table.direction;
  double fraction = 0, travel_time = 0;
  ramp_profile(ramp, ramp_time, t, fraction, travel_time);
  return travel_time * velocity;
}

Vec3 WallMotion::velocity_at(double t) const {
  if (t < start_time) return Vec3::Zero();
  t -= start_time;
  if (!table.time.empty()) return table_speed(table, t) * table.direction;
  double fraction = 0, travel_time = 0;
  ramp_profile(ramp, ramp_time, t, fraction, travel_time);
  return fraction * velocity;
}

double WallMotion::angle_at(double t) const {
  if (!spins || t <= start_time) return 0.0;
  t -= start_time;
  if (!spin_table.time.empty()) return table_travel(spin_table, t);
  double fraction = 0, travel_time = 0;
  ramp_profile(ramp, ramp_time, t, fraction, travel_time);
  return travel_time * angular_speed;
}

double WallMotion::angular_speed_at(double t) const {
  if (!spins || t < start_time) return 0.0;
  t -= start_time;
  if (!spin_table.time.empty()) return table_speed(spin_table, t);
  double fraction = 0, travel_time = 0;
  ramp_profile(ramp, ramp_time, t, fraction, travel_time);
  return fraction * angular_speed;
}

}  // namespace shard
