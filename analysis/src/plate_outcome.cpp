#include "shard/analysis/plate_outcome.hpp"

#include <map>
#include <stdexcept>

#include "shard/analysis/run_tables.hpp"

namespace shard::analysis {

std::vector<PlateOutcome> plate_outcomes(const BodyReport& report, const std::vector<Fragment>& fragments,
                                         const std::string& run, double value, std::int64_t seed) {
  std::map<std::int32_t, std::vector<const Fragment*>> pieces;
  for (const Fragment& f : fragments) pieces[f.body].push_back(&f);
  std::vector<PlateOutcome> out;
  out.reserve(report.bodies.size());
  for (const BodyStatistics& b : report.bodies) {
    PlateOutcome p;
    p.run = run;
    p.value = value;
    p.seed = seed;
    p.body = b.body;
    p.impacted = b.impacted;
    p.impact_speed = b.impact_speed;
    p.impact_angle = b.impact_angle;
    p.broken = b.broken;
    p.fragments = b.fragments;
    p.mass = b.mass;
    p.largest_fraction = b.largest_fraction;
    p.x10 = b.fsd.x10;
    p.x50 = b.fsd.x50;
    p.x90 = b.fsd.x90;
    p.fines_mass = b.fsd.fines_mass;
    for (const Fragment* f : pieces[b.body]) {
      p.fragment_d.push_back(f->d_eq);
      p.fragment_mass.push_back(f->mass);
    }
    out.push_back(std::move(p));
  }
  return out;
}

RunBodies analyse_run_bodies(const RunFile& file, std::optional<std::int64_t> frame, double intact_fraction,
                             double fines_size, std::optional<double> density) {
  const std::vector<std::size_t>& frames = file.frames();
  if (frames.empty()) throw std::runtime_error(file.path().string() + " holds no frame yet");
  RunBodies out;
  out.frame = frame.value_or(static_cast<std::int64_t>(frames.back()));
  const FrameData f = file.read_frame(static_cast<std::size_t>(out.frame), density);
  out.time = f.time;
  out.fragments = analyse_fragments(particle_sample(f), bond_list(f)).fragments;
  out.report = body_statistics(particle_sample(f), out.fragments, intact_fraction, fines_size);
  attach_impacts(out.report, file.read_body_impacts());
  return out;
}

}  // namespace shard::analysis
