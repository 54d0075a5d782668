#include "bending_fixture.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <vector>

#include "shard/bending/test_setup.hpp"
#include "shard/measure/significant_digits.hpp"
#include "shard/plugin_host.hpp"
#include "shard/scene.hpp"
#include "shard/simulation.hpp"

namespace shard {

namespace fs = std::filesystem;

SceneOverrides BendingFixture::seating_overrides(const fs::path& scene_file, const SceneOverrides& overrides) const {
  const Scene scene = load_scene(scene_file, host_, overrides);
  if (scene.stop.load_walls.empty()) return {};
  const Vec3 n = scene.stop.load_direction.normalized();
  const SceneInstance inst = instantiate(scene, host_, [](const std::string&) {});
  const Particles& p = inst.simulation->particles();
  SceneOverrides out;
  for (const Wall& w : scene.walls) {
    if (w.shape != WallShape::Cylinder) continue;
    const bool loading = scene.stop.is_load_wall(w.name);
    if (!loading && w.velocity.norm() > 0) continue;
    // A loading pin arrives along +n (first contact = smallest offset); a support waits on the far
    // side and is brought against the body along -n (largest offset).
    double best = loading ? std::numeric_limits<double>::infinity() : -std::numeric_limits<double>::infinity();
    for (std::size_t k = 0; k < p.size(); ++k) {
      const double s = cylinder_touch_offset(w, n, p.position[k], p.radius[k], loading);
      if (std::isnan(s)) continue;
      best = loading ? std::min(best, s) : std::max(best, s);
    }
    if (!std::isfinite(best)) continue;  // nothing under this cylinder: leave it where it is
    out.push_back({fmt::format("wall.{}.point", w.name), significant(Vec3(w.point + best * n), 12)});
  }
  return out;
}

SpecimenSetup BendingFixture::specimen_setup(const fs::path& scene_file, const SceneOverrides& overrides,
                                             long seed) const {
  SceneOverrides seeded = overrides;
  seeded.push_back({"simulation.seed", std::int64_t{seed}});
  const Scene scene = load_scene(scene_file, host_, seeded);
  std::vector<const Wall*> pins, supports;
  for (const Wall& w : scene.walls) {
    if (w.shape != WallShape::Cylinder) continue;
    if (scene.stop.is_load_wall(w.name)) pins.push_back(&w);
    else if (w.velocity.norm() == 0) supports.push_back(&w);
  }
  if (pins.size() != 2 || supports.size() != 2)
    throw std::runtime_error(fmt::format(
        "{}: {} loading and {} resting cylinders; the specimen's span and pin distance are read from two of each "
        "(four-point bending). Give them explicitly (--length, --width, --height, --span, --pin-distance)",
        scene_file.string(), pins.size(), supports.size()));
  const bending::BeamFrame frame = bending::beam_frame(pins[0]->point, pins[1]->point, scene.stop.load_direction);
  const SceneInstance inst = instantiate(scene, host_, [](const std::string&) {});
  const Particles& p = inst.simulation->particles();
  const bending::SphereExtent extent = bending::sphere_extent(frame, p.position, p.radius);
  SpecimenSetup s;
  s.pin_distance = bending::distance_along(frame, pins[0]->point, pins[1]->point);
  s.span = bending::distance_along(frame, supports[0]->point, supports[1]->point);
  s.length = extent.length, s.width = extent.width, s.height = extent.height;
  for (double r : p.radius) s.particle_diameter = std::max(s.particle_diameter, 2 * r);
  return s;
}

double BendingFixture::scene_rate(const fs::path& scene_file, const SceneOverrides& overrides) const {
  const Scene scene = load_scene(scene_file, host_, overrides);
  double rate = 0;
  for (const Wall& w : scene.walls)
    if (scene.stop.is_load_wall(w.name))
      rate = std::max(rate, w.velocity.norm());
  return rate;
}

SceneOverrides BendingFixture::rate_overrides(const fs::path& scene_file, const SceneOverrides& overrides, double rate) const {
  const Scene scene = load_scene(scene_file, host_, overrides);
  const double own = scene_rate(scene_file, overrides);
  if (!(own > 0))
    throw std::runtime_error(fmt::format("{}: no moving [stop] load_walls, so the loading rate cannot be set to {} m/s",
                                         scene_file.string(), rate));
  if (std::abs(rate - own) <= 1e-9 * own) return {};
  const double f = rate / own;
  SceneOverrides out;
  for (const Wall& w : scene.walls)
    if (scene.stop.is_load_wall(w.name)) {
      out.push_back({fmt::format("wall.{}.velocity", w.name), significant(Vec3(f * w.velocity), 12)});
      // The same ramp travel at the new speed: the ramp is f times shorter.
      if (w.motion.ramp != WallRamp::None)
        out.push_back({fmt::format("wall.{}.ramp_time", w.name), significant(w.motion.ramp_time / f, 12)});
    }
  out.push_back({"simulation.duration", significant(scene.duration / f, 12)});
  if (scene.series_interval > 0) out.push_back({"output.series_interval", significant(scene.series_interval / f, 12)});
  return out;
}

SceneOverrides BendingFixture::ramp_overrides(const fs::path& scene_file, const SceneOverrides& overrides,
                                       const std::string& ramp, double ramp_time) const {
  const Scene scene = load_scene(scene_file, host_, overrides);
  SceneOverrides out;
  for (const Wall& w : scene.walls)
    if (scene.stop.is_load_wall(w.name)) {
      out.push_back({fmt::format("wall.{}.ramp", w.name), ramp});
      // With ramp = "none" a ramp_time of the scene's is ignored (the loader allows that pair).
      if (ramp != "none") out.push_back({fmt::format("wall.{}.ramp_time", w.name), significant(ramp_time, 12)});
    }
  return out;
}

}  // namespace shard
