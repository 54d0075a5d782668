#include "shard/analysis/body_statistics.hpp"

#include <map>
#include <stdexcept>

namespace shard::analysis {

BodyReport body_statistics(const ParticleSample& particles, const std::vector<Fragment>& fragments,
                           double intact_fraction, double fines_size) {
  if (!(intact_fraction > 0 && intact_fraction <= 1))
    throw std::invalid_argument("body statistics: the intact fraction must lie in (0, 1]");
  check_sample(particles);
  BodyReport report;
  report.intact_fraction = intact_fraction;
  std::map<std::int32_t, BodyStatistics> by_id;
  for (std::size_t v = 0; v < particles.size(); ++v) {
    const std::int32_t id = particles.body.empty() ? 0 : particles.body[v];
    BodyStatistics& b = by_id[id];
    b.body = id;
    ++b.particles;
    b.mass += particles.mass[v];
  }
  std::map<std::int32_t, std::vector<Fragment>> pieces;
  for (const Fragment& f : fragments) pieces[f.body].push_back(f);
  for (auto& [id, b] : by_id) {
    const std::vector<Fragment>& own = pieces[id];
    b.fragments = own.size();
    double largest = 0;
    for (const Fragment& f : own) largest = std::max(largest, f.mass);
    b.largest_fraction = b.mass > 0 ? largest / b.mass : 0;
    // One fragment is an intact body whatever the rounding of the two mass sums.
    b.broken = b.fragments > 1 && b.largest_fraction < intact_fraction;
    b.fsd = size_distribution(own, fines_size);
    report.broken += b.broken ? 1 : 0;
    report.bodies.push_back(b);
  }
  report.breakage_probability =
      report.bodies.empty() ? 0 : static_cast<double>(report.broken) / static_cast<double>(report.bodies.size());
  report.pooled = size_distribution(fragments, fines_size);
  return report;
}

void attach_impacts(BodyReport& report, const std::vector<BodyImpact>& impacts) {
  for (BodyStatistics& b : report.bodies) {
    if (b.body < 0 || static_cast<std::size_t>(b.body) >= impacts.size()) continue;
    const BodyImpact& impact = impacts[static_cast<std::size_t>(b.body)];
    b.impacted = impact.hit;
    b.impact_time = impact.time;
    // As the run wrote them into /body_impacts (speed, angle): the same functions of the same numbers.
    b.impact_speed = impact.speed();
    b.impact_angle = impact.angle_degrees();
    b.impact_wall = impact.wall;
  }
}

}  // namespace shard::analysis
