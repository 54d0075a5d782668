#include "bench_scenes.hpp"

#include <cmath>
#include <random>

#include "shard/generator.hpp"

namespace shard::bench {
namespace {

constexpr double kDiameter = 1e-3;  // m
constexpr double kDensity = 2500;   // kg/m^3
// fcc with nearest-neighbour distance d holds sqrt(2)/d^3 spheres per unit volume.
const double kFccPerVolume = std::sqrt(2.0) / (kDiameter * kDiameter * kDiameter);

GeneratedBody fill(const Vec3& hi, double d_min, bool bond) {
  auto& h = host();
  const ParamSet params = h.params(PluginKind::Generator, "box_fill",
                                   {{"min_corner", Vec3(Vec3::Zero())}, {"max_corner", hi}, {"lattice", std::string("fcc")},
                                    {"diameter_min", d_min}, {"diameter_max", kDiameter}, {"bond", bond}});
  GeneratorContext context;
  context.seed = 7;
  return h.make_generator("box_fill", params)->generate(context);
}

Particles particles_of(const GeneratedBody& body, double radius_scale) {
  Particles p;
  p.reserve(body.position.size());
  for (std::size_t k = 0; k < body.position.size(); ++k) p.add(body.position[k], radius_scale * body.radius[k], kDensity);
  return p;
}

}  // namespace

PluginHost& host() {
  static PluginHost h;
  static const bool loaded = [] {
    h.load_directories(PluginHost::default_search_path());
    return true;
  }();
  (void)loaded;
  return h;
}

Models default_models(const std::map<std::string, ParamValue>& bond_params) {
  auto& h = host();
  Models m;
  m.contact = h.make_contact("hertz_mindlin", h.params(PluginKind::Contact, "hertz_mindlin", {}));
  m.bond = h.make_bond("beam_bond", h.params(PluginKind::Bond, "beam_bond", bond_params));
  return m;
}

SimulationSetup bonded_block(std::size_t target, double pull_speed, const Models& models) {
  // Box 2a x a x a with 2 a^3 * density = target.
  const double a = std::cbrt(static_cast<double>(target) / (2 * kFccPerVolume));
  const GeneratedBody body = fill(Vec3(2 * a, a, a), kDiameter, true);
  SimulationSetup s;
  s.particles = particles_of(body, 1.0);
  s.bonds = body.bonds;
  s.contact = models.contact.get();
  s.bond = models.bond.get();
  double x_lo = 1e300, x_hi = -1e300;
  for (const Vec3& x : s.particles.position) {
    x_lo = std::min(x_lo, x.x());
    x_hi = std::max(x_hi, x.x());
  }
  for (std::size_t k = 0; k < s.particles.size(); ++k) {
    const double x = s.particles.position[k].x();
    if (x < x_lo + 1.5 * kDiameter || x > x_hi - 1.5 * kDiameter) {
      s.particles.flags[k] = kPrescribed;
      s.particles.velocity[k] = Vec3(x < x_lo + 1.5 * kDiameter ? -pull_speed : pull_speed, 0, 0);
    }
  }
  return s;
}

SimulationSetup dense_pack(std::size_t target, const Models& models) {
  const double a = std::cbrt(static_cast<double>(target) / kFccPerVolume);
  const GeneratedBody body = fill(Vec3(a, a, a), 0.96 * kDiameter, false);
  SimulationSetup s;
  s.particles = particles_of(body, 1.02);
  std::mt19937_64 rng(11);
  std::normal_distribution<double> normal(0, 0.05 / std::sqrt(3.0));
  for (auto& v : s.particles.velocity) v = Vec3(normal(rng), normal(rng), normal(rng));
  s.contact = models.contact.get();
  s.gravity = Vec3(0, 0, -9.81);
  double lo = 1e300, hi = -1e300;
  for (std::size_t k = 0; k < s.particles.size(); ++k) {
    lo = std::min(lo, s.particles.position[k].minCoeff() - s.particles.radius[k]);
    hi = std::max(hi, s.particles.position[k].maxCoeff() + s.particles.radius[k]);
  }
  for (int axis = 0; axis < 3; ++axis) {
    for (int side = 0; side < 2; ++side) {
      if (axis == 2 && side == 1) continue;  // open top
      Wall w;
      w.name = "wall" + std::to_string(2 * axis + side);
      w.axis = Vec3::Zero();
      w.axis[axis] = side == 0 ? 1.0 : -1.0;
      w.point = Vec3::Zero();
      w.point[axis] = side == 0 ? lo : hi;
      s.walls.push_back(w);
    }
  }
  return s;
}

}  // namespace shard::bench
