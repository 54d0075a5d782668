#include "shard/analysis/run_tables.hpp"

#include <cstdint>

namespace shard::analysis {

ParticleSample particle_sample(const FrameData& frame) {
  return {frame.id, frame.position, frame.velocity, frame.radius, frame.mass, frame.body};
}

BondList bond_list(const FrameData& frame) { return {frame.bond_i, frame.bond_j}; }

RunTable fragment_run_table(const std::vector<Fragment>& fragments, const SizeDistribution& fsd) {
  const std::size_t count = fragments.size();
  std::vector<std::int64_t> particles(count);
  std::vector<std::int32_t> body(count);
  std::vector<double> mass(count), volume(count), d_eq(count);
  std::vector<Vec3> centre(count), velocity(count), box_min(count), box_max(count);
  for (std::size_t r = 0; r < count; ++r) {
    const Fragment& f = fragments[r];
    particles[r] = static_cast<std::int64_t>(f.particles);
    body[r] = f.body;
    mass[r] = f.mass;
    volume[r] = f.volume;
    d_eq[r] = f.d_eq;
    centre[r] = f.centre;
    velocity[r] = f.velocity;
    box_min[r] = f.box_min;
    box_max[r] = f.box_max;
  }
  RunTable table;
  table.columns = {{"particles", std::move(particles)}, {"mass", std::move(mass)},   {"volume", std::move(volume)},
                   {"d_eq", std::move(d_eq)},           {"centre", std::move(centre)}, {"velocity", std::move(velocity)},
                   {"box_min", std::move(box_min)},     {"box_max", std::move(box_max)}, {"body", std::move(body)}};
  table.figures = {{"count", static_cast<std::int64_t>(count)}, {"x10", fsd.x10}, {"x50", fsd.x50},
                   {"x90", fsd.x90}, {"fines_size", fsd.fines_size}, {"fines_mass", fsd.fines_mass}};
  return table;
}

void write_fragment_table(RunFile& file, std::size_t k, const std::vector<Fragment>& fragments,
                          const SizeDistribution& fsd) {
  file.write_table("fragments/" + frame_name(k), fragment_run_table(fragments, fsd));
}

RunTable body_run_table(const BodyReport& report) {
  const std::size_t count = report.bodies.size();
  std::vector<std::int32_t> body(count), broken(count), impacted(count);
  std::vector<std::int64_t> particles(count), fragments(count);
  std::vector<double> mass(count), largest(count), x10(count), x50(count), x90(count), fines(count);
  std::vector<double> impact_time(count), impact_speed(count), impact_angle(count);
  for (std::size_t r = 0; r < count; ++r) {
    const BodyStatistics& b = report.bodies[r];
    body[r] = b.body;
    broken[r] = b.broken ? 1 : 0;
    particles[r] = static_cast<std::int64_t>(b.particles);
    fragments[r] = static_cast<std::int64_t>(b.fragments);
    mass[r] = b.mass;
    largest[r] = b.largest_fraction;
    x10[r] = b.fsd.x10;
    x50[r] = b.fsd.x50;
    x90[r] = b.fsd.x90;
    fines[r] = b.fsd.fines_mass;
    impacted[r] = b.impacted ? 1 : 0;
    impact_time[r] = b.impact_time;
    impact_speed[r] = b.impact_speed;
    impact_angle[r] = b.impact_angle;
  }
  RunTable table;
  table.columns = {{"body", std::move(body)},
                   {"broken", std::move(broken)},
                   {"particles", std::move(particles)},
                   {"fragments", std::move(fragments)},
                   {"mass", std::move(mass)},
                   {"largest_fraction", std::move(largest)},
                   {"x10", std::move(x10)},
                   {"x50", std::move(x50)},
                   {"x90", std::move(x90)},
                   {"fines_mass", std::move(fines)},
                   {"impacted", std::move(impacted)},
                   {"impact_time", std::move(impact_time)},
                   {"impact_speed", std::move(impact_speed)},
                   {"impact_angle", std::move(impact_angle)}};
  table.figures = {{"count", static_cast<std::int64_t>(count)},
                   {"broken_count", static_cast<std::int64_t>(report.broken)},
                   {"breakage_probability", report.breakage_probability},
                   {"intact_fraction", report.intact_fraction},
                   {"x10", report.pooled.x10},
                   {"x50", report.pooled.x50},
                   {"x90", report.pooled.x90},
                   {"fines_size", report.pooled.fines_size},
                   {"fines_mass", report.pooled.fines_mass}};
  return table;
}

void write_body_table(RunFile& file, std::size_t k, const BodyReport& report) {
  file.write_table("bodies/" + frame_name(k), body_run_table(report));
}

}  // namespace shard::analysis
