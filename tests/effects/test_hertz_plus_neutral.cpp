// At its neutral values hertz_mindlin_plus must be hertz_mindlin: both shipped plugin files,
// random particle-particle and particle-wall contacts over 50 steps of history (sticking and
// sliding), forces, couples, energies and histories bit-identical.
#include <doctest/doctest.h>

#include <cstring>
#include <map>
#include <random>

#include "contact_batch.hpp"
#include "shard/plugin_host.hpp"

namespace shard::effects_test {

TEST_CASE("hertz_mindlin_plus at neutral values is bit-identical to hertz_mindlin") {
  PluginHost host;
  host.load_file(SHARD_BUILD_DIR "/plugins/shard_hertz_mindlin.so");
  host.load_file(SHARD_BUILD_DIR "/plugins/shard_hertz_mindlin_plus.so");
  std::map<std::string, ParamValue> neutral;
  for (const auto& spec : host.find(PluginKind::Contact, "hertz_mindlin_plus").info.params)
    if (spec.name == "wall_friction" || spec.name == "cohesion_stress") {
      REQUIRE(spec.neutral.has_value());
      neutral[spec.name] = *spec.neutral;
    }
  REQUIRE(neutral.size() == 2);
  const auto base = host.make_contact("hertz_mindlin", host.params(PluginKind::Contact, "hertz_mindlin", {}));
  const auto plus = host.make_contact("hertz_mindlin_plus", host.params(PluginKind::Contact, "hertz_mindlin_plus", neutral));
  REQUIRE(base->history_size() == plus->history_size());
  CHECK(base->time_step_limit(0.35e-3, 3720).recommended == plus->time_step_limit(0.35e-3, 3720).recommended);

  const std::size_t n = 1000;
  ContactScene a(n, base->history_size());
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-1, 1);
  for (std::size_t k = 0; k < n; ++k) {
    a.j[k] = k % 4 == 0 ? -1 - static_cast<Index>(k % 3) : 1;  // a quarter at walls
    a.r_eff[k] = 0.2e-3 * (1.5 + u(rng));
    a.m_eff[k] = 1e-6 * (1.5 + u(rng));
  }
  ContactScene b = a;
  std::size_t sliding = 0;
  for (int step = 0; step < 50; ++step) {
    for (std::size_t k = 0; k < n; ++k) {
      Vec3 nrm(u(rng), u(rng), u(rng));
      const Vec3 normal = (Vec3::UnitZ() + 0.05 * nrm).normalized();
      const double delta = 1e-6 * (1.2 + u(rng));
      const Vec3 velocity(0.05 * u(rng), 0.05 * u(rng), 0.01 * u(rng));
      a.normal[k] = b.normal[k] = normal;
      a.overlap[k] = b.overlap[k] = delta;
      a.velocity[k] = b.velocity[k] = velocity;
    }
    a.compute(*base, 1e-6);
    b.compute(*plus, 1e-6);
    for (std::size_t k = 0; k < n; ++k) {
      CHECK(std::memcmp(a.force[k].data(), b.force[k].data(), 3 * sizeof(double)) == 0);
      CHECK(std::memcmp(a.couple[k].data(), b.couple[k].data(), 3 * sizeof(double)) == 0);
      CHECK(std::memcmp(&a.energy[k], &b.energy[k], sizeof(double)) == 0);
      const Vec3 f_t = a.force[k] - a.force[k].dot(a.normal[k]) * a.normal[k];
      const double f_n = a.force[k].dot(a.normal[k]);
      if (f_t.norm() >= 0.67 * f_n * (1 - 1e-12)) ++sliding;
    }
    CHECK(std::memcmp(a.history.data(), b.history.data(), a.history.size() * sizeof(double)) == 0);
  }
  MESSAGE(sliding, " of ", 50 * n, " contact evaluations at the Coulomb cap");
  CHECK(sliding > 1000);  // both branches compared
}

}  // namespace shard::effects_test
