#pragma once
// Small worlds built in code for the kernel tests: plugins come from the build tree.
#include <memory>
#include <random>

#include "shard/plugin_host.hpp"
#include "shard/simulation.hpp"

namespace shard::test {

inline PluginHost& plugins() {
  static PluginHost host;  // loading once per test binary keeps the suite fast
  static bool loaded = false;
  if (!loaded) {
    host.load_directories(PluginHost::default_search_path());
    loaded = true;
  }
  return host;
}

inline std::unique_ptr<ContactModel> linear_spring(double k = 1e4, double e = 0.5, double mu = 0.5) {
  auto& host = plugins();
  return host.make_contact("linear_spring", host.params(PluginKind::Contact, "linear_spring",
                                                        {{"normal_stiffness", k}, {"restitution", e}, {"friction", mu}}));
}

// A gas of non-overlapping spheres in a cube of side L with random velocities.
inline Particles random_gas(std::size_t n, double side, double radius, unsigned seed) {
  Particles p;
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  const int per_side = static_cast<int>(std::ceil(std::cbrt(static_cast<double>(n))));
  const double spacing = side / per_side;
  for (std::size_t k = 0; k < n; ++k) {
    const int ix = static_cast<int>(k) % per_side, iy = (static_cast<int>(k) / per_side) % per_side,
              iz = static_cast<int>(k) / (per_side * per_side);
    const Vec3 x = (Vec3(ix, iy, iz) + Vec3::Constant(0.5)) * spacing;
    p.add(x, radius * (0.8 + 0.2 * u(rng)), 2500.0);
    p.velocity.back() = Vec3(u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5);
  }
  return p;
}

inline std::vector<Wall> box_walls(double side) {
  std::vector<Wall> walls;
  for (int axis = 0; axis < 3; ++axis)
    for (int s = 0; s < 2; ++s) {
      Wall w;
      w.shape = WallShape::Plane;
      w.axis = Vec3::Zero();
      w.axis[axis] = s == 0 ? 1.0 : -1.0;
      w.point = Vec3::Zero();
      w.point[axis] = s == 0 ? 0.0 : side;
      walls.push_back(w);
    }
  return walls;
}

}  // namespace shard::test
