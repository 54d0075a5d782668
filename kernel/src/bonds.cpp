#include "shard/bonds.hpp"

namespace shard {

void Bonds::resize(std::size_t n) {
  i.resize(n);
  j.resize(n);
  state.resize(n * stride);
  force.assign(n, Vec3::Zero());
  torque_i.assign(n, Vec3::Zero());
  torque_j.assign(n, Vec3::Zero());
  energy.assign(n, 0.0);
  broken.assign(n, 0);
  stress.assign(n, BondStress{});
}

std::size_t Bonds::remove_broken() {
  std::size_t kept = 0;
  const std::size_t n = size();
  for (std::size_t k = 0; k < n; ++k) {
    if (broken[k]) continue;
    if (kept != k) {
      i[kept] = i[k];
      j[kept] = j[k];
      for (std::size_t s = 0; s < stride; ++s) state[kept * stride + s] = state[k * stride + s];
      force[kept] = force[k];
      torque_i[kept] = torque_i[k];
      torque_j[kept] = torque_j[k];
      energy[kept] = energy[k];
    }
    ++kept;
  }
  const std::size_t removed = n - kept;
  // Shrinking never reallocates, so the step loop stays allocation-free.
  i.resize(kept);
  j.resize(kept);
  state.resize(kept * stride);
  force.resize(kept);
  torque_i.resize(kept);
  torque_j.resize(kept);
  energy.resize(kept);
  broken.assign(kept, 0);
  stress.resize(kept);
  return removed;
}

}  // namespace shard
