// hertz_mindlin's batch runs in SIMD lanes without branches (hertz_lanes.cpp); it must give the
// per-contact code's results bit for bit (HertzMindlin::compute_reference), in every regime the
// branches of that code separate: sticking and sliding, the no-pull clamp, a spring turned onto
// the plane and one that lies along the normal, new contacts, and a partial last group of lanes.
#include <doctest/doctest.h>

#include <cmath>
#include <cstring>
#include <random>

#include "contact_arrays.hpp"
#include "hertz_mindlin_model.hpp"

using namespace shard;
using namespace shard::test;

namespace {

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

bool same_bits(const Vec3& a, const Vec3& b) {
  return same_bits(a.x(), b.x()) && same_bits(a.y(), b.y()) && same_bits(a.z(), b.z());
}

Vec3 random_unit(std::mt19937_64& rng) {
  std::normal_distribution<double> g;
  Vec3 v(g(rng), g(rng), g(rng));
  return v / v.norm();
}

// Contacts of a bonded solid and a dense pack: overlaps from 1e-9 to 1e-4 m, speeds up to 1 m/s,
// histories zero, small, at the Coulomb cap and beyond it, and some exactly along the normal.
ContactArrays random_contacts(std::size_t n, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  ContactArrays c(n, 3);
  for (std::size_t k = 0; k < n; ++k) {
    const Vec3 normal = random_unit(rng);
    c.normal[k] = normal;
    c.j[k] = k % 7 == 0 ? -1 : Index(k + 1);
    c.overlap[k] = std::pow(10.0, -9.0 + 5.0 * u(rng));
    c.r_eff[k] = (0.2 + 0.8 * u(rng)) * 1e-3;
    c.m_eff[k] = (0.5 + u(rng)) * 1e-6;
    const double speed = std::pow(10.0, -6.0 + 6.0 * u(rng));
    c.velocity[k] = k % 11 == 0 ? Vec3::Zero() : Vec3(speed * random_unit(rng));
    c.omega_rel[k] = random_unit(rng);
    Vec3 spring = std::pow(10.0, -12.0 + 9.0 * u(rng)) * random_unit(rng);
    switch (k % 5) {
      case 0: spring = Vec3::Zero(); break;                   // a new contact
      case 1: spring = spring.norm() * Vec3::UnitX(); break;  // along the normal below
      default: break;
    }
    if (k % 5 == 1) c.normal[k] = Vec3::UnitX();
    for (int q = 0; q < 3; ++q) c.history[3 * k + static_cast<std::size_t>(q)] = spring[q];
  }
  return c;
}

struct Regimes {
  std::size_t sliding = 0, clamped = 0, along_normal = 0;
};

Regimes compare(const HertzMindlinMaterial& material, std::size_t n, unsigned seed, double dt) {
  const HertzMindlin model(material);
  const double friction = material.friction;
  ContactArrays lanes = random_contacts(n, seed);
  ContactArrays reference = random_contacts(n, seed);
  ContactBatch a = lanes.batch(dt);
  ContactBatch b = reference.batch(dt);
  model.compute(a);
  model.compute_reference(b);
  Regimes seen;
  bool same = true;
  for (std::size_t k = 0; k < n; ++k) {
    CAPTURE(k);
    const Vec3 spring(reference.history[3 * k], reference.history[3 * k + 1], reference.history[3 * k + 2]);
    const Vec3 lane_spring(lanes.history[3 * k], lanes.history[3 * k + 1], lanes.history[3 * k + 2]);
    const bool ok = same_bits(lanes.force[k], reference.force[k]) && same_bits(lanes.energy[k], reference.energy[k]) &&
                    same_bits(lane_spring, spring);
    if (!ok) CHECK(ok);
    same = same && ok;
    // Regimes, from the reference's force: F_n clamped to zero, or |F_t| at the Coulomb cap.
    const double f_n = reference.force[k].dot(reference.normal[k]);
    const double f_t = (reference.force[k] - f_n * reference.normal[k]).norm();
    if (f_n == 0.0) ++seen.clamped;
    else if (f_t > 0.0 && std::abs(f_t - friction * f_n) < 1e-9 * f_t) ++seen.sliding;
    if (k % 5 == 1) ++seen.along_normal;
  }
  CHECK(same);
  return seen;
}

}  // namespace

TEST_CASE("hertz_mindlin's lanes give the per-contact results bit for bit") {
  for (const std::size_t n : {std::size_t{1}, std::size_t{7}, std::size_t{128}, std::size_t{1001}}) {
    CAPTURE(n);
    for (const double dt : {1e-7, 2e-6}) {
      const Regimes seen = compare(HertzMindlinMaterial{}, n, static_cast<unsigned>(n) + 3, dt);
      if (n == 1001) {
        // The regimes the per-contact code branches on all occur.
        CHECK(seen.sliding > 10);
        CHECK(seen.clamped > 10);
        CHECK(seen.along_normal > 100);
      }
    }
  }
}

TEST_CASE("hertz_mindlin's lanes without friction or damping match too") {
  HertzMindlinMaterial frictionless;
  frictionless.friction = 0.0;
  frictionless.restitution = 1.0;
  compare(frictionless, 333, 9, 1e-6);
  HertzMindlinMaterial lossy;
  lossy.restitution = 0.1;
  lossy.friction = 2.0;
  compare(lossy, 333, 10, 1e-6);
}
