// The law at the SIMD width of each instruction set (beam_batch.hpp) against the same law at width 1
// (compute_reference). Tolerance: none. Every width runs the same IEEE operations in the same
// order without fused multiply-adds (-ffp-contract=off), and a lane's operations do not depend
// on its neighbours, so every force, torque, energy, break flag and break stress must be
// bit-identical (a build that fused or reordered would need a few ulp here), for small and
// large deformations, moving ends, bonds listed either way round, with and without damping and
// breakage, with the effect policies composed in (their state too), and block sizes that leave a
// partial last block.
#include <doctest/doctest.h>

#include <stdexcept>
#include <string>
#include <vector>

#include "beam_batch.hpp"
#include "beam_bond_model.hpp"
#include "beam_geometry.hpp"
#include "bond_pair.hpp"
#include "random_bonds.hpp"

using namespace shard;
using namespace shard::beam;

namespace {

struct Counts {
  std::size_t compared = 0, broken = 0;
};

// Every instruction set this CPU runs, the widest first.
std::vector<BlockIsa> runnable() {
  std::vector<BlockIsa> out;
  for (const BlockIsa isa : {BlockIsa::Avx512, BlockIsa::Avx2, BlockIsa::Baseline})
    if (runs_here(isa)) out.push_back(isa);
  return out;
}

Counts compare(const BeamBondParams& params, std::size_t pairs, std::uint64_t seed, BlockIsa isa) {
  const BeamBond model(params, isa);
  test::HandBonds a = test::random_pairs<test::HandBonds>(pairs, seed, {true, true});
  a.dt = 1e-6;  // the Maxwell arm reads the step
  a.initialize(model);
  test::HandBonds b = a;
  Counts n;
  const double scales[] = {1e-6, 1e-4, 1e-3, 3e-3, 1e-2, 0.05, 0.2, 0.6};
  for (std::size_t step = 0; step < std::size(scales); ++step) {
    test::deform(a, 100 + step, scales[step], 1.0);
    test::deform(b, 100 + step, scales[step], 1.0);
    BondBatch ba = a.batch(model), bb = b.batch(model);
    model.compute(ba);
    model.compute_reference(bb);
    n.compared += a.i.size();
    n.broken += test::check_same_outputs(a, b);
    // The per-bond state too (damage, the arm's strains): the next step starts from it.
    for (std::size_t k = 0; k < a.state.size(); ++k) REQUIRE(test::same_bits(a.state[k], b.state[k]));
  }
  return n;
}

}  // namespace

TEST_CASE("blocked beam_bond step is bit-identical to the per-bond path, on every instruction set") {
  BeamBondParams defaults;
  for (const BlockIsa isa : runnable()) {
    const std::string isa_name = name_of(isa);
    CAPTURE(isa_name);
    MESSAGE("block step ", std::string(name_of(isa)));
    SUBCASE("Table I defaults (no force damping)") {
      const Counts n = compare(defaults, 1001, 3, isa);
      MESSAGE(n.compared, " bond evaluations, ", n.broken, " breaks");
      CHECK(n.broken > 100);
    }
    SUBCASE("viscous force and rotational damping") {
      BeamBondParams p = defaults;
      p.damping = 1e-3;
      p.rotational_damping = 0.5;
      p.radius_ratio = 0.8;
      p.shear_modulus = 4e6;
      compare(p, 777, 5, isa);
    }
    SUBCASE("all four effects on, with damping") {
      BeamBondParams p = defaults;
      p.damping = 1e-3;
      p.effects.strength_weibull_modulus = 4;
      p.effects.softening_ratio = 2;
      p.effects.viscosity_time = 2e-6;  // two steps: the arm's stress is a large share of the load
      p.effects.compression_stiffness_ratio = 2;
      REQUIRE(BeamBond(p, isa).with_effects());
      const Counts n = compare(p, 1001, 11, isa);
      MESSAGE(n.compared, " bond evaluations with effects, ", n.broken, " breaks");
      CHECK(n.broken > 100);
    }
    SUBCASE("three effects on, without the Maxwell arm") {
      BeamBondParams p = defaults;
      p.effects.strength_weibull_modulus = 4;
      p.effects.softening_ratio = 2;
      p.effects.compression_stiffness_ratio = 0.5;
      REQUIRE(BeamBond(p, isa).state_size() == kEffectsStateSize);
      const Counts n = compare(p, 1001, 12, isa);
      CHECK(n.broken > 100);
    }
    SUBCASE("effects named at their neutral values") {
      BeamBondParams p = defaults;
      p.effects.named = {"weibull_strength", "softening", "viscosity", "compression_asymmetry"};
      REQUIRE(BeamBond(p, isa).with_effects());
      compare(p, 500, 13, isa);
    }
    SUBCASE("no breakage, no rotational damping") {
      BeamBondParams p = defaults;
      p.breakage = false;
      p.rotational_damping = 0;
      const Counts n = compare(p, 130, 9, isa);
      CHECK(n.broken == 0);
    }
  }
}

TEST_CASE("the baseline block step runs everywhere; a wider one is refused where the CPU lacks it") {
  // The model's default is the widest of the variants this CPU runs (runnable() lists widest first).
  CHECK(widest_block_isa() == runnable().front());
  for (const BlockIsa isa : {BlockIsa::Avx512, BlockIsa::Avx2})
    if (!runs_here(isa)) CHECK_THROWS_AS(BeamBond(BeamBondParams{}, isa), std::invalid_argument);
}

TEST_CASE("the blocked lanes take the common case: small rotations, below strength") {
  // Straight bonds between identity-oriented spheres; a few lanes made rare on purpose.
  test::HandBonds s;
  for (std::size_t l = 0; l < kBlockLanes; ++l) {
    const Index a = s.add_sphere(Vec3(0, 0.01 * static_cast<double>(l), 0), 0.5e-3);
    s.add_sphere(Vec3(1e-3, 0.01 * static_cast<double>(l), 0), 0.5e-3);
    s.add_bond(a, a + 1);
  }
  const BeamBond model(BeamBondParams{});
  s.initialize(model);
  s.state[3 * kStateSize + 5] = 0.5;  // reference frame off unit length
  s.orientation[2 * 5 + 1] = Quat(std::cos(0.2), 0, 0, std::sin(0.2));  // 23 deg: outside the series
  s.position[2 * 7 + 1].x() = 1.1e-3;  // 10 % strain: may reach the strength
  const BlockConstants& c = model.block_constants();
  BondBatch batch = s.batch(model);
  BlockInput in;
  in.i = s.i.data();
  in.j = s.j.data();
  in.state = s.state.data();
  in.position = s.position[0].data();
  in.velocity = s.velocity[0].data();
  in.orientation = s.orientation[0].coeffs().data();
  in.omega = s.omega[0].data();
  in.radius = s.radius.data();
  in.inertia = s.inertia.data();
  BlockOutput out{};
  out.force = s.force[0].data();
  out.torque_i = s.torque_i[0].data();
  out.torque_j = s.torque_j[0].data();
  out.energy = s.energy.data();
  for (const BlockIsa isa : runnable()) {
    const std::string isa_name = name_of(isa);
    CAPTURE(isa_name);
    block_function(isa)(in, out, kBlockLanes, c);
    for (std::size_t l = 0; l < kBlockLanes; ++l) CHECK(((out.fallback >> l) & 1) == (l == 3 || l == 5 || l == 7 ? 1u : 0u));
  }
  // And the whole model agrees with the per-bond path on them.
  test::HandBonds r = s;
  BondBatch rb = r.batch(model);
  model.compute(batch);
  model.compute_reference(rb);
  test::check_same_outputs(s, r);
}
