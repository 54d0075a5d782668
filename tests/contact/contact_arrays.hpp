#pragma once
// Hand-built ContactBatch storage for calling a contact model the way the kernel does.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "shard/contact_model.hpp"

namespace shard::test {

struct ContactArrays {
  ContactArrays(std::size_t n, std::size_t history_stride)
      : i(n, 0), j(n, 1), normal(n, Vec3::UnitX()), velocity(n, Vec3::Zero()), omega_rel(n, Vec3::Zero()),
        force(n), couple(n), overlap(n, 0.0), r_eff(n, 0.0), m_eff(n, 0.0), energy(n), history(n * history_stride, 0.0) {}

  std::vector<Index> i, j;
  std::vector<Vec3> normal, velocity, omega_rel, force, couple;
  std::vector<double> overlap, r_eff, m_eff, energy, history;
  std::vector<std::int32_t> material_pair;  // empty: one material (ContactBatch::material_pair null)

  // A batch over all contacts with the outputs zeroed, as the kernel hands it over.
  ContactBatch batch(double dt) {
    std::fill(force.begin(), force.end(), Vec3::Zero());
    std::fill(couple.begin(), couple.end(), Vec3::Zero());
    std::fill(energy.begin(), energy.end(), 0.0);
    ContactBatch b;
    b.count = i.size();
    b.dt = dt;
    b.i = i.data();
    b.j = j.data();
    b.normal = normal.data();
    b.overlap = overlap.data();
    b.velocity = velocity.data();
    b.omega_rel = omega_rel.data();
    b.r_eff = r_eff.data();
    b.m_eff = m_eff.data();
    b.history = history.data();
    b.force = force.data();
    b.couple = couple.data();
    b.energy = energy.data();
    b.material_pair = material_pair.empty() ? nullptr : material_pair.data();
    return b;
  }
};

inline double relative_difference(double a, double b) {
  const double scale = std::max(std::abs(a), std::abs(b));
  return scale == 0.0 ? 0.0 : std::abs(a - b) / scale;
}

}  // namespace shard::test
