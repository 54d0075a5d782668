#pragma once
// The kernel's ContactBatch as the plain arrays a lane kernel reads (contact_lanes.hpp).
#include "contact_lanes.hpp"
#include "shard/contact_model.hpp"

namespace shard::contact {

inline ContactArrays arrays_of(ContactBatch& b) {
  // Vec3 is three packed doubles (Eigen::Matrix<double, 3, 1>, no padding), so an array of them
  // is x, y, z interleaved.
  static_assert(sizeof(Vec3) == 3 * sizeof(double));
  if (b.count == 0) return {};
  return {b.count, b.dt, b.j, b.normal->data(), b.velocity->data(), b.overlap, b.r_eff, b.m_eff, b.history,
          b.force->data(), b.energy, b.material_pair, b.omega_rel ? b.omega_rel->data() : nullptr,
          b.couple ? b.couple->data() : nullptr};
}

}  // namespace shard::contact
