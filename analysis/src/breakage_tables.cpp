#include "shard/analysis/breakage_tables.hpp"

#include <fmt/format.h>

#include <cstdint>

namespace shard::analysis {
namespace {

template <class T, class F>
std::vector<T> column(std::size_t n, F&& f) {
  std::vector<T> out(n);
  for (std::size_t k = 0; k < n; ++k) out[k] = static_cast<T>(f(k));
  return out;
}

}  // namespace

ColumnTable plate_table(const std::vector<PlateOutcome>& plates, const std::string& value_name) {
  const std::size_t n = plates.size();
  const auto& p = plates;
  ColumnTable t;
  t.add("run", column<std::string>(n, [&](std::size_t k) { return p[k].run; }));
  if (!value_name.empty()) {
    t.add(value_name, column<double>(n, [&](std::size_t k) { return p[k].value; }));
    t.add("seed", column<std::int64_t>(n, [&](std::size_t k) { return p[k].seed; }));
  }
  t.add("body", column<std::int64_t>(n, [&](std::size_t k) { return p[k].body; }))
      .add("impacted", column<std::int64_t>(n, [&](std::size_t k) { return p[k].impacted ? 1 : 0; }))
      .add("impact_speed_m_s", column<double>(n, [&](std::size_t k) { return p[k].impact_speed; }))
      .add("impact_angle_deg", column<double>(n, [&](std::size_t k) { return p[k].impact_angle; }))
      .add("broken", column<std::int64_t>(n, [&](std::size_t k) { return p[k].broken ? 1 : 0; }))
      .add("fragments", column<std::int64_t>(n, [&](std::size_t k) { return p[k].fragments; }))
      .add("largest_fraction", column<double>(n, [&](std::size_t k) { return p[k].largest_fraction; }))
      .add("x10_m", column<double>(n, [&](std::size_t k) { return p[k].x10; }))
      .add("x50_m", column<double>(n, [&](std::size_t k) { return p[k].x50; }))
      .add("x90_m", column<double>(n, [&](std::size_t k) { return p[k].x90; }))
      .add("fines_mass_kg", column<double>(n, [&](std::size_t k) { return p[k].fines_mass; }))
      .add("mass_kg", column<double>(n, [&](std::size_t k) { return p[k].mass; }));
  t.note("description", "one row per plate (parent body); impact = first wall contact (/body_impacts)");
  return t;
}

ColumnTable group_table(const std::vector<BreakageGroup>& groups, GroupedBy by, const CurveOptions& options,
                        const std::string& value_name) {
  const std::size_t n = groups.size();
  const auto& g = groups;
  ColumnTable t;
  if (by == GroupedBy::impact_speed) {
    t.add("speed_lower_m_s", column<double>(n, [&](std::size_t k) { return g[k].lower; }));
    t.add("speed_upper_m_s", column<double>(n, [&](std::size_t k) { return g[k].upper; }));
  } else {
    t.add(value_name, column<double>(n, [&](std::size_t k) { return g[k].lower; }));
  }
  t.add("plates", column<std::int64_t>(n, [&](std::size_t k) { return g[k].plates; }))
      .add("broken", column<std::int64_t>(n, [&](std::size_t k) { return g[k].broken; }))
      .add("broken_share", column<double>(n, [&](std::size_t k) { return g[k].broken_share; }))
      .add("broken_share_lower", column<double>(n, [&](std::size_t k) { return g[k].broken_interval.lower; }))
      .add("broken_share_upper", column<double>(n, [&](std::size_t k) { return g[k].broken_interval.upper; }))
      .add("not_impacted", column<std::int64_t>(n, [&](std::size_t k) { return g[k].not_impacted; }))
      .add("mean_impact_speed_m_s", column<double>(n, [&](std::size_t k) { return g[k].mean_speed; }))
      .add("min_impact_speed_m_s", column<double>(n, [&](std::size_t k) { return g[k].min_speed; }))
      .add("max_impact_speed_m_s", column<double>(n, [&](std::size_t k) { return g[k].max_speed; }))
      .add("fragments", column<std::int64_t>(n, [&](std::size_t k) { return g[k].fragments; }))
      .add("x10_m", column<double>(n, [&](std::size_t k) { return g[k].x10; }))
      .add("x50_m", column<double>(n, [&](std::size_t k) { return g[k].x50; }))
      .add("x50_lower_m", column<double>(n, [&](std::size_t k) { return g[k].x50_interval.lower; }))
      .add("x50_upper_m", column<double>(n, [&](std::size_t k) { return g[k].x50_interval.upper; }))
      .add("x90_m", column<double>(n, [&](std::size_t k) { return g[k].x90; }));
  t.note("grouped_by", by == GroupedBy::impact_speed ? "impact speed bins [lower, upper), the last closed"
                                                      : fmt::format("the swept value {}", value_name));
  t.note("broken_share_interval", fmt::format("Wilson score interval, z = {:.16g}", options.z));
  t.note("x50_interval", fmt::format("bootstrap percentile interval, level {:g}, {} resamples of the plates, seed {}",
                                     options.level, options.resamples, options.seed));
  t.note("x50", "mass-weighted median of the equivalent diameters of all fragments of the group's plates");
  return t;
}

}  // namespace shard::analysis
