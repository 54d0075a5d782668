#pragma once
// Software prefetch of the particle rows that the next block of bonds or tile of listed pairs will
// read and write, issued one block ahead. Bonds and pairs are sorted by their smaller index, so
// their smaller ends' rows stream in order and the hardware prefetcher fetches them; the larger
// end lies a jump along the Morton curve ahead. In a scene whose particles do not fit in the
// caches (the seed beam: 330 283 spheres, ~70 MB of particle rows), each such row would come from
// memory as a miss inside the force law, one group of lanes after another; requested a block
// ahead, the misses overlap each other and the arithmetic. A prefetch changes no value: the state stays
// bit-identical.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "shard/particles.hpp"

namespace shard {

// Both lines a row of T may straddle (a Vec3 of 24 bytes does at 3 offsets of 8 in a line).
template <class T>
[[gnu::always_inline]] inline void prefetch_row(const T* rows, std::size_t k) {
  const char* first = reinterpret_cast<const char*>(rows + k);
  __builtin_prefetch(first);
  __builtin_prefetch(first + sizeof(T) - 1);
}

template <class T>
[[gnu::always_inline]] inline void prefetch_row_for_write(T* rows, std::size_t k) {
  char* first = reinterpret_cast<char*>(rows + k);
  __builtin_prefetch(first, 1);
  __builtin_prefetch(first + sizeof(T) - 1, 1);
}

// The larger ends of bonds [0, count) (i, j): what a bond model reads of them (position,
// orientation, spin, radius, inertia, the stable id that orders a bond's ends) and the loads they
// receive (`force`, `torque`: the thread's arrays).
inline void prefetch_bond_ends(const Particles& p, const Index* i, const Index* j, std::size_t count, Vec3* force,
                               Vec3* torque) {
  for (std::size_t k = 0; k < count; ++k) {
    const auto far = static_cast<std::size_t>(std::max(i[k], j[k]));
    prefetch_row(p.position.data(), far);
    prefetch_row(p.orientation.data(), far);
    prefetch_row(p.omega.data(), far);
    prefetch_row(p.radius.data(), far);
    prefetch_row(p.inertia.data(), far);
    prefetch_row(p.id.data(), far);
    prefetch_row_for_write(force, far);
    prefetch_row_for_write(torque, far);
  }
}

// The larger ends of listed pairs [begin, end) (second < 0: a wall, nothing to fetch): the
// candidate test's position and radius; for a pair that touched at the last pass, and so most
// likely touches now, also the contact geometry's velocity, spin and mass and the loads it
// receives. A pair that did not touch names its smaller end there instead (already in cache): no
// branch on the touching flag, which is close to random.
inline void prefetch_pair_ends(const Particles& p, const Index* first, const Index* second,
                               const std::uint8_t* touching, std::size_t begin, std::size_t end, Vec3* force,
                               Vec3* torque) {
  for (std::size_t q = begin; q < end; ++q) {
    const Index a = first[q], b = second[q];
    if (b < 0) continue;
    const auto near = static_cast<std::size_t>(std::min(a, b)), far = static_cast<std::size_t>(std::max(a, b));
    prefetch_row(p.position.data(), far);
    prefetch_row(p.radius.data(), far);
    const std::size_t touched = touching[q] ? far : near;
    prefetch_row(p.velocity.data(), touched);
    prefetch_row(p.omega.data(), touched);
    prefetch_row(p.mass.data(), touched);
    prefetch_row_for_write(force, touched);
    prefetch_row_for_write(torque, touched);
  }
}

}  // namespace shard
