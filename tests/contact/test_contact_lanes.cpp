// Each contact law is written once for a lane type (plugins/contact/common/contact_lanes.hpp) and
// compiled per instruction set; the scalar instance (T = double) is the reference. Tolerance: none,
// bit for bit. Each lane performs the reference's IEEE operations (+ - * / sqrt, selects) in the
// same order, no multiply-add is fused (-ffp-contract=off), so any difference is a bug, not
// rounding. Checked in every regime the scalar code selects between: sticking and sliding, the
// no-pull clamp, a spring turned onto the plane and one along the normal, new contacts, walls and
// particles, each effect policy on and off, and a partial last block of lanes.
#include <doctest/doctest.h>

#include <cmath>
#include <cstring>
#include <random>

#include "contact_arrays.hpp"
#include "hertz_mindlin_model.hpp"
#include "linear_spring_model.hpp"

using namespace shard;
using namespace shard::test;
using contact::LaneSet;

namespace {

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

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
    c.normal[k] = random_unit(rng);
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
  std::size_t sliding = 0, clamped = 0;
};

// Every instruction set this machine runs against the scalar instance, over three steps (the
// springs carry over); returns the regimes of the first step.
// `pairs` > 0: each contact of a random pair of materials in [0, pairs) (the law table's rows).
template <class Model>
Regimes compare(const Model& model, double friction, std::size_t n, unsigned seed, double dt, std::int32_t pairs = 0) {
  Regimes seen;
  for (const LaneSet set : {LaneSet::baseline, LaneSet::avx2, LaneSet::avx512}) {
    if (!contact::lane_set_available(set)) continue;
    CAPTURE(contact::lane_set_name(set));
    ContactArrays lanes = random_contacts(n, seed), reference = random_contacts(n, seed);
    if (pairs > 0) {
      std::mt19937 rng(seed);
      for (std::size_t k = 0; k < n; ++k) lanes.material_pair.push_back(static_cast<std::int32_t>(rng() % pairs));
      reference.material_pair = lanes.material_pair;
    }
    for (int step = 0; step < 3; ++step) {
      ContactBatch a = lanes.batch(dt), b = reference.batch(dt);
      model.compute_with(set, a);
      model.compute_with(LaneSet::scalar, b);
      std::size_t differing = 0;
      for (std::size_t k = 0; k < n; ++k) {
        bool ok = same_bits(lanes.energy[k], reference.energy[k]);
        for (int q = 0; q < 3; ++q)
          ok = ok && same_bits(lanes.force[k][q], reference.force[k][q]) &&
               same_bits(lanes.history[3 * k + q], reference.history[3 * k + q]);
        differing += ok ? 0 : 1;
        if (step > 0 || set != LaneSet::baseline) continue;
        const double f_n = reference.force[k].dot(reference.normal[k]);
        const double f_t = (reference.force[k] - f_n * reference.normal[k]).norm();
        if (f_n == 0.0) ++seen.clamped;
        else if (f_t > 0.0 && std::abs(f_t - friction * f_n) < 1e-9 * f_t) ++seen.sliding;
      }
      CAPTURE(step);
      CHECK(differing == 0);
    }
  }
  return seen;
}

}  // namespace

TEST_CASE("hertz_mindlin: every instruction set's lanes give the scalar results bit for bit") {
  const HertzMindlin plain{HertzMindlinMaterial{}};
  for (const std::size_t n : {std::size_t{1}, std::size_t{7}, std::size_t{128}, std::size_t{1001}}) {
    CAPTURE(n);
    for (const double dt : {1e-7, 2e-6}) {
      const Regimes seen = compare(plain, 0.67, n, static_cast<unsigned>(n) + 3, dt);
      if (n == 1001) {
        // The regimes the scalar code selects between all occur.
        CHECK(seen.sliding > 10);
        CHECK(seen.clamped > 10);
      }
    }
  }
  HertzMindlinMaterial frictionless;
  frictionless.friction = 0.0;
  frictionless.restitution = 1.0;
  compare(HertzMindlin(frictionless), 0.0, 333, 9, 1e-6);
  HertzMindlinMaterial lossy;
  lossy.restitution = 0.1;
  lossy.friction = 2.0;
  compare(HertzMindlin(lossy), 2.0, 333, 10, 1e-6);
}

TEST_CASE("hertz_mindlin with each effect policy: every instruction set bit for bit") {
  for (const double sigma : {0.0, 5e4})
    for (const double ratio : {1.0, 0.15}) {
      contact::ContactEffects effects;
      effects.cohesion_stress = sigma;
      effects.support_friction_ratio = ratio;
      effects.named = {"cohesion", "support_friction"};
      CAPTURE(sigma);
      CAPTURE(ratio);
      compare(HertzMindlin(HertzMindlinMaterial{}, effects), 0.67, 1001, 21, 1e-6);
    }
}

TEST_CASE("linear_spring: every instruction set's lanes give the scalar results bit for bit") {
  const LinearSpring plain{LinearSpringParameters{}};
  for (const std::size_t n : {std::size_t{1}, std::size_t{5}, std::size_t{1001}}) {
    CAPTURE(n);
    compare(plain, 0.67, n, static_cast<unsigned>(n) + 5, 1e-6);
  }
  contact::ContactEffects support;
  support.support_friction_ratio = 0.15;
  compare(LinearSpring(LinearSpringParameters{}, support), 0.67, 1001, 30, 1e-6);
}

namespace {

// Three materials, a soft cake, a stiff rubber-like one and steel (docs/reference/materials.md), each pair
// with its own friction and restitution.
ContactMaterials three_materials(bool hertz) {
  ContactMaterials m;
  m.count = 3;
  m.names = {"cake", "rubber", "steel"};
  const double shear[] = {10e6, 0.4e6, 79e9}, poisson[] = {0.25, 0.49, 0.3};
  for (std::size_t a = 0; a < 3; ++a) {
    ParamSet p;
    p.set("shear_modulus", shear[a]);
    p.set("poisson_ratio", poisson[a]);
    m.material.push_back(p);
  }
  for (std::size_t a = 0; a < 3; ++a)
    for (std::size_t b = 0; b < 3; ++b) {
      const std::size_t lo = std::min(a, b), hi = std::max(a, b);
      ParamSet p;
      p.set("friction", 0.2 + 0.3 * static_cast<double>(lo) + 0.1 * static_cast<double>(hi));
      p.set("restitution", 0.3 + 0.1 * static_cast<double>(lo + hi));
      if (!hertz) {
        p.set("normal_stiffness", 1e3 * static_cast<double>(1 + lo + 2 * hi));
        p.set("tangential_stiffness_ratio", 2.0 / 7.0);
      }
      m.pair.push_back(p);
    }
  return m;
}

}  // namespace

TEST_CASE("materials: each lane gathers its pair's law; every instruction set bit for bit") {
  HertzMindlin hertz{HertzMindlinMaterial{}};
  hertz.set_materials(three_materials(true));
  LinearSpring linear{LinearSpringParameters{}};
  linear.set_materials(three_materials(false));
  for (const std::size_t n : {std::size_t{1}, std::size_t{7}, std::size_t{1001}}) {
    CAPTURE(n);
    compare(hertz, -1.0, n, static_cast<unsigned>(n) + 40, 1e-6, 9);
    compare(linear, -1.0, n, static_cast<unsigned>(n) + 50, 1e-6, 9);
  }
  contact::ContactEffects effects;
  effects.cohesion_stress = 5e4;
  effects.support_friction_ratio = 0.15;
  HertzMindlin with_effects{HertzMindlinMaterial{}, effects};
  with_effects.set_materials(three_materials(true));
  compare(with_effects, -1.0, 1001, 61, 1e-6, 9);
}

TEST_CASE("materials: a pair of one material's contacts equal the one-material law's, bit for bit") {
  // Pair (a, a) of the table against a model built for material a alone with the pair's mu and e:
  // the gather reads the right row and the alike forms of E* and G* are the constructor's.
  const ContactMaterials table = three_materials(true);
  HertzMindlin mixed{HertzMindlinMaterial{}};
  mixed.set_materials(table);
  for (std::int32_t a = 0; a < 3; ++a) {
    CAPTURE(a);
    const std::size_t row = static_cast<std::size_t>(a) * 4;
    const HertzMindlin alone{HertzMindlinMaterial{table.material[static_cast<std::size_t>(a)].number("shear_modulus"),
                                                  table.material[static_cast<std::size_t>(a)].number("poisson_ratio"),
                                                  table.pair[row].number("friction"),
                                                  table.pair[row].number("restitution")}};
    ContactArrays by_table = random_contacts(257, 70), by_model = random_contacts(257, 70);
    by_table.material_pair.assign(257, a * 3 + a);
    for (const LaneSet set : {LaneSet::scalar, LaneSet::baseline, LaneSet::avx2, LaneSet::avx512}) {
      if (!contact::lane_set_available(set)) continue;
      ContactBatch x = by_table.batch(1e-6), y = by_model.batch(1e-6);
      mixed.compute_with(set, x);
      alone.compute_with(set, y);
      std::size_t differing = 0;
      for (std::size_t k = 0; k < 257; ++k)
        for (int q = 0; q < 3; ++q) differing += same_bits(by_table.force[k][q], by_model.force[k][q]) ? 0 : 1;
      CHECK(differing == 0);
    }
  }
  // A mixed pair is softer than the softer material against itself: E* from both moduli.
  const double soft = mixed.law(1, 1).constant[hertz::HertzLaw::kForceFactor];
  const double rubber_steel = mixed.law(1, 2).constant[hertz::HertzLaw::kForceFactor];
  CHECK(rubber_steel > soft);       // steel is stiffer than rubber: E*(rubber, steel) ~ 2 E*(rubber, rubber)
  CHECK(rubber_steel < 2.0 * soft);
  CHECK(mixed.law(1, 2).constant[hertz::HertzLaw::kForceFactor] == mixed.law(2, 1).constant[hertz::HertzLaw::kForceFactor]);
}
