#include "shard/bonds.hpp"

namespace shard {

void Bonds::resize(std::size_t n) {
  i.resize(n);
  j.resize(n);
  state.resize(n * stride);
  set_keeps_loads(keeps_loads);
  broken.assign(n, 0);
  stress.assign(n, BondStress{});
}

void Bonds::set_keeps_loads(bool keep) {
  keeps_loads = keep;
  const std::size_t loads = keep ? size() : 0;
  force.assign(loads, Vec3::Zero());
  torque_i.assign(loads, Vec3::Zero());
  torque_j.assign(loads, Vec3::Zero());
  energy.assign(loads, 0.0);
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
      if (keeps_loads) {
        force[kept] = force[k];
        torque_i[kept] = torque_i[k];
        torque_j[kept] = torque_j[k];
        energy[kept] = energy[k];
      }
    }
    ++kept;
  }
  const std::size_t removed = n - kept;
  // Shrinking never reallocates, so the step loop stays allocation-free.
  i.resize(kept);
  j.resize(kept);
  state.resize(kept * stride);
  const std::size_t loads = keeps_loads ? kept : 0;
  force.resize(loads);
  torque_i.resize(loads);
  torque_j.resize(loads);
  energy.resize(loads);
  broken.assign(kept, 0);
  stress.resize(kept);
  return removed;
}

}  // namespace shard
