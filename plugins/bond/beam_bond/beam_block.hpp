#pragma once
// The block step at the SIMD width of architecture A: the bonds of a block, W = batch size at a
// time, gathered into lanes, run through beam_law at that width, and scattered back. Included
// only by beam_block_<isa>.cpp, each compiled for its instruction set (beam_batch.hpp).
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <type_traits>

#include "beam_batch.hpp"
#include "beam_law.hpp"
#include "shard/lanes/xsimd_lanes.hpp"

namespace shard::beam {

template <class A, bool breakage, bool viscous, bool effects, bool arm>
[[gnu::always_inline]] inline void evaluate_lanes(const BlockInput& in, BlockOutput& out, std::size_t n,
                                                  const BlockConstants& c) {
  using T = xsimd::batch<double, A>;
  using L = lanes::Lanes<T>;
  using Idx = typename L::index;
  constexpr std::size_t W = L::width;
  constexpr std::size_t stride = !effects ? kStateSize : arm ? kViscousStateSize : kEffectsStateSize;
  // Lanes past n repeat bond n - 1: they compute its very bits and store them into its slots, so
  // the last, partial group needs no masked loads or stores. The element offsets of each lane's
  // fields (index times the field's width) are made here once. The state is gathered and the
  // loads scattered: measured faster than copying them through transposed lane arrays (plain
  // 53.4-54.1 against 56.9-57.5 CPU ns per bond-step, all four effects 78.0-78.1 against 92.3-93.3).
  alignas(64) std::int64_t first[3][kBlockLanes], second[3][kBlockLanes], slot[3][kBlockLanes];
  alignas(64) double swapped[kBlockLanes];
  // Each bond's ends in its own order (beam_geometry.hpp, ends_of) first, one bond at a time (the
  // ids are gathered); then the offsets, a loop GCC vectorises.
  const std::size_t padded = (n + W - 1) / W * W;
  for (std::size_t l = 0; l < padded; ++l) {
    const std::size_t k = std::min(l, n - 1);
    const Index i = in.i[k], j = in.j[k];
    const bool swap = in.id ? in.id[j] < in.id[i] : j < i;
    first[0][l] = swap ? j : i;
    second[0][l] = swap ? i : j;
    swapped[l] = swap ? 1.0 : 0.0;
  }
  for (std::size_t l = 0; l < padded; ++l) {
    const std::size_t k = std::min(l, n - 1);
    first[1][l] = 3 * first[0][l], first[2][l] = 4 * first[0][l];
    second[1][l] = 3 * second[0][l], second[2][l] = 4 * second[0][l];
    slot[0][l] = static_cast<std::int64_t>(k);
    slot[1][l] = static_cast<std::int64_t>(3 * k);
    slot[2][l] = static_cast<std::int64_t>(stride * k);
  }
  for (std::size_t base = 0; base < padded; base += W) {
    // The state streams from memory (9 to 23 doubles a bond, megabytes a batch) and the lanes'
    // loads wait on each miss: the lines of the group after next (in this block or the next,
    // which follows it in the batch) are requested now. A prefetch past the array is harmless.
    const char* ahead = reinterpret_cast<const char*>(in.state + (base + 2 * W) * stride);
    for (std::size_t byte = 0; byte < W * stride * sizeof(double); byte += 64) __builtin_prefetch(ahead + byte);
    const Idx a = L::load_index(first[0] + base), b = L::load_index(second[0] + base);
    BondLanes<T> bond;
    // Each lane's rows: Quat stored x, y, z, w (Eigen's order), Vec3 x, y, z, the state.
    T q1[4], q2[4];
    L::template load_rows<4>(in.orientation, first[2] + base, q1);
    L::template load_rows<4>(in.orientation, second[2] + base, q2);
    bond.q1 = {q1[3], q1[0], q1[1], q1[2]};
    bond.q2 = {q2[3], q2[0], q2[1], q2[2]};
    L::template load_rows<3>(in.position, first[1] + base, bond.x1);
    L::template load_rows<3>(in.position, second[1] + base, bond.x2);
    L::template load_rows<3>(in.omega, first[1] + base, bond.w1);
    L::template load_rows<3>(in.omega, second[1] + base, bond.w2);
    if constexpr (viscous) {
      L::template load_rows<3>(in.velocity, first[1] + base, bond.v1);
      L::template load_rows<3>(in.velocity, second[1] + base, bond.v2);
    }
    bond.r1 = L::gather(in.radius, a);
    bond.r2 = L::gather(in.radius, b);
    bond.i1 = L::gather(in.inertia, a);
    bond.i2 = L::gather(in.inertia, b);
    const Idx k = L::load_index(slot[0] + base), k3 = L::load_index(slot[1] + base);
    const Idx ks = L::load_index(slot[2] + base);
    L::template load_rows<stride>(in.state, slot[2] + base, bond.state);

    const BondLoads<T> r = beam_law<T, false, breakage, viscous, effects, arm>(bond, c, NoExtraCriterion{});

    // In the batch's orientation: force and torque_i on batch.i (a selection: which end a batch
    // lists first is close to random, a branch would be mispredicted).
    const auto sw = L::load(swapped + base) != 0.0;
    T force[3], torque_i[3], torque_j[3];
    for (int d = 0; d < 3; ++d) {
      force[d] = select(sw, -r.force[d], r.force[d]);
      torque_i[d] = select(sw, r.torque_second[d], r.torque_first[d]);
      torque_j[d] = select(sw, r.torque_first[d], r.torque_second[d]);
    }
    if (base + W <= n) {
      // A whole group writes W consecutive slots. AVX-512 interleaves the three components in
      // registers (lanes::store3); its scatter instruction is slower. Narrower sets keep the
      // scatter, which xsimd writes as the same single stores.
      if constexpr (std::is_same_v<A, xsimd::avx512f>) {
        lanes::store3(out.force + 3 * base, force[0], force[1], force[2]);
        lanes::store3(out.torque_i + 3 * base, torque_i[0], torque_i[1], torque_i[2]);
        lanes::store3(out.torque_j + 3 * base, torque_j[0], torque_j[1], torque_j[2]);
      } else {
        for (int d = 0; d < 3; ++d) {
          L::scatter(out.force + d, k3, force[d]);
          L::scatter(out.torque_i + d, k3, torque_i[d]);
          L::scatter(out.torque_j + d, k3, torque_j[d]);
        }
      }
      L::store(out.energy + base, r.energy);
    } else {  // the last group's lanes past n write bond n - 1's slots again
      for (int d = 0; d < 3; ++d) {
        L::scatter(out.force + d, k3, force[d]);
        L::scatter(out.torque_i + d, k3, torque_i[d]);
        L::scatter(out.torque_j + d, k3, torque_j[d]);
      }
      L::scatter(out.energy, k, r.energy);
    }
    out.fallback |= L::bits(r.fallback) << base;
    if constexpr (arm)  // a fallback lane keeps its state for its own width-1 step
      for (std::size_t s = 0; s < 12; ++s)
        L::scatter(out.state + kPreviousStrainSlot + s, ks,
                   select(r.fallback, bond.state[kPreviousStrainSlot + s], r.next_arm[s]));
  }
}

template <class A, bool effects, bool arm>
inline void evaluate_law(const BlockInput& in, BlockOutput& out, std::size_t n, const BlockConstants& c) {
  if (c.breakage) {
    if (c.viscous_force) evaluate_lanes<A, true, true, effects, arm>(in, out, n, c);
    else evaluate_lanes<A, true, false, effects, arm>(in, out, n, c);
  } else {
    if (c.viscous_force) evaluate_lanes<A, false, true, effects, arm>(in, out, n, c);
    else evaluate_lanes<A, false, false, effects, arm>(in, out, n, c);
  }
}

template <class A>
inline void evaluate_block(const BlockInput& in, BlockOutput& out, std::size_t n, const BlockConstants& c) {
  out.fallback = 0;
  if (n == 0) return;
  if (!c.effects) evaluate_law<A, false, false>(in, out, n, c);
  else if (c.arm) evaluate_law<A, true, true>(in, out, n, c);
  else evaluate_law<A, true, false>(in, out, n, c);
  if (n < 64) out.fallback &= (std::uint64_t{1} << n) - 1;  // the lanes past n repeat bond n - 1
}

}  // namespace shard::beam
