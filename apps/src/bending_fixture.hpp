#pragma once
// The four-point bending fixture of a scene as the measurement commands set it up, each change as
// scene overrides that a run records and a user can repeat.
//
// Seating: a testing machine brings the pins into contact before it records. The loading walls
// ([stop] load_walls) and the resting cylinders (supports) are moved along the loading direction
// until they just touch the generated packing, so a random packing's uneven surface does not add
// a seed-dependent toe gap to the curve.
#include <filesystem>
#include <string>

#include "shard/scene_override.hpp"

namespace shard {

class PluginHost;

// A bending scene's specimen as a measurement describes it (m): the extent of the generated
// packing along the beam (the line between the loading pins, across the loading direction),
// across it and along the load; the distances between the two supports and the two pins.
struct SpecimenSetup {
  double length = 0, width = 0, height = 0, span = 0, pin_distance = 0;
  double particle_diameter = 0;  // the largest sphere's, m
};

class BendingFixture {
 public:
  // `host` (with the scene's plugins loaded) must outlive the fixture.
  explicit BendingFixture(const PluginHost& host) : host_(host) {}

  // The overrides that seat the walls of `scene` (with `overrides`, the packing seed among them) on
  // its packing (empty without load walls).
  SceneOverrides seating_overrides(const std::filesystem::path& scene, const SceneOverrides& overrides) const;
  // The overrides that load `scene` (with `overrides`) at `rate` m/s instead of its own pin
  // speed: the load walls' velocities scaled, and the duration and the series interval scaled
  // inversely so that the same pin travel is simulated and recorded. Empty at the scene's rate.
  SceneOverrides rate_overrides(const std::filesystem::path& scene, const SceneOverrides& overrides, double rate) const;
  // The overrides that accelerate the [stop] load walls along `ramp` ("1-cos", "linear", "none")
  // over `ramp_time` s (the kernel's [[wall]] ramp).
  SceneOverrides ramp_overrides(const std::filesystem::path& scene, const SceneOverrides& overrides,
                                const std::string& ramp, double ramp_time) const;
  // The specimen of a scene (generated with `seed`); throws unless the scene has two loading
  // cylinders ([stop] load_walls) and two resting cylinders (supports).
  SpecimenSetup specimen_setup(const std::filesystem::path& scene, const SceneOverrides& overrides, long seed) const;
  // The pin speed of a scene, m/s: the largest speed of its [stop] load walls.
  double scene_rate(const std::filesystem::path& scene, const SceneOverrides& overrides) const;
 private:
  const PluginHost& host_;
};

}  // namespace shard
