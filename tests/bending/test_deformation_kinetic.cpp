// The quasi-static check's kinetic energy is the deformation's, not the rigid-body motion's
// (shard/analysis/deformation_kinetic.hpp): a beam sliding on its rollers is not a dynamic test,
// a beam loaded ten times faster than its scene's rate is.
#include <doctest/doctest.h>

#include <random>
#include <sstream>

#include "shard/app/run_command.hpp"
#include "shard/analysis/deformation_kinetic.hpp"

using shard::Particles;
using shard::Vec3;

namespace {

Particles cloud(std::size_t n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> pos(-0.02, 0.02), rad(0.001, 0.0013);
  Particles p;
  for (std::size_t k = 0; k < n; ++k) {
    const double r = rad(rng), m = 3720.0 * 4.18879 * r * r * r;
    p.position.push_back({pos(rng), 0.2 * pos(rng), 0.2 * pos(rng)});
    p.velocity.push_back(Vec3::Zero());
    p.omega.push_back(Vec3::Zero());
    p.radius.push_back(r);
    p.mass.push_back(m);
    p.inertia.push_back(0.4 * m * r * r);
  }
  return p;
}

double total_kinetic(const Particles& p) {
  double e = 0;
  for (std::size_t k = 0; k < p.size(); ++k)
    e += 0.5 * (p.mass[k] * p.velocity[k].squaredNorm() + p.inertia[k] * p.omega[k].squaredNorm());
  return e;
}

void add_rigid_motion(Particles& p, const Vec3& v, const Vec3& w) {
  for (std::size_t k = 0; k < p.size(); ++k) {
    p.velocity[k] += v + w.cross(p.position[k]);  // about the origin: any point of a rigid body will do
    p.omega[k] += w;
  }
}

}  // namespace

TEST_CASE("rigid-body motion carries no deformation kinetic energy; a strain rate keeps all of its own") {
  Particles p = cloud(400, 7);
  add_rigid_motion(p, {0.02, -0.01, 0.005}, {1.5, -0.7, 3.0});
  // Rounding of sums of ~400 terms: relative 1e-12 of the total is far below any physical motion.
  CHECK(shard::analysis::deformation_kinetic_energy(p) < 1e-12 * total_kinetic(p));

  // A breathing motion v = a (x - c) about the centre of mass c has no momentum and no angular
  // momentum: all of its kinetic energy is deformation, with or without a rigid motion on top.
  Particles q = cloud(400, 8);
  double m = 0;
  Vec3 c = Vec3::Zero();
  for (std::size_t k = 0; k < q.size(); ++k) m += q.mass[k], c += q.mass[k] * q.position[k];
  c /= m;
  for (std::size_t k = 0; k < q.size(); ++k) q.velocity[k] = 0.5 * (q.position[k] - c);
  const double breathing = total_kinetic(q);
  CHECK(shard::analysis::deformation_kinetic_energy(q) == doctest::Approx(breathing).epsilon(1e-9).scale(0));
  add_rigid_motion(q, {0.3, 0.0, -0.1}, {0.0, 2.0, 0.0});
  CHECK(total_kinetic(q) > 2 * breathing);
  CHECK(shard::analysis::deformation_kinetic_energy(q) == doctest::Approx(breathing).epsilon(1e-9).scale(0));
  CHECK(shard::analysis::deformation_kinetic_energy(cloud(1, 9)) == 0.0);
}

TEST_CASE("the tiny beam is quasi-static at its own rate and dynamic at ten times it") {
  // scenes/measurements/tiny_bending.toml, seed 1001, pins at full speed from the start. Measured:
  // 0.0059 at 0.02 m/s and 0.22 at 0.2 m/s (from the total kinetic energy: 0.026 and 1.36, so the
  // scene's own rate read as dynamic).
  auto ratio_at = [](double speed) {
    shard::RunOptions o;
    o.scene = std::filesystem::path(SHARD_SOURCE_DIR) / "scenes/measurements/tiny_bending.toml";
    o.out_dir = "deformation_kinetic_" + std::to_string(static_cast<int>(1000 * speed));
    o.plugin_dirs = {std::filesystem::path(SHARD_BUILD_DIR) / "plugins"};
    o.threads = 1;
    o.quiet = true;
    const double f = speed / 0.02;
    o.overrides = {{"simulation.seed", std::int64_t{1001}},
                   {"wall.pin_left.velocity", shard::Vec3(0, 0, -speed)},
                   {"wall.pin_right.velocity", shard::Vec3(0, 0, -speed)},
                   {"simulation.duration", 0.15 / f},
                   {"output.series_interval", 1e-4 / f}};
    std::ostringstream log;
    return shard::run_scene(o, log).max_kinetic_to_elastic;
  };
  // The bound the measurement commands warn above (kDynamicKineticToElastic, 0.01).
  CHECK(ratio_at(0.02) < 0.01);
  CHECK(ratio_at(0.2) > 0.01);
}
