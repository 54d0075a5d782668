// DistributedSimulation::gather_frame: what a frame of the run file holds (docs/reference/output-format.md),
// gathered to one rank, and nothing more: gather_state's particle records carry orientation, force,
// torque, inertia and flags besides (22 doubles against 11), and its bonds their model state
// (2 + stride doubles against two 32-bit ids), which a frame drops.
#include <algorithm>
#include <array>
#include <cstdint>
#include <limits>
#include <utility>
#include <stdexcept>

#include <fmt/format.h>

#include "comm.hpp"
#include "global_rows.hpp"
#include "halo.hpp"
#include "shard/domain_exchange.hpp"
#include "shard/mpi/distributed_simulation.hpp"

namespace shard::mpi {
namespace {

struct FrameRecord {
  double position[3], velocity[3], omega[3];
  double radius, mass;
  std::int32_t material, body;
  Index id;
};

FrameRecord frame_record_of(const Particles& p, std::size_t k) {
  FrameRecord r{};
  std::copy_n(p.position[k].data(), 3, r.position);
  std::copy_n(p.velocity[k].data(), 3, r.velocity);
  std::copy_n(p.omega[k].data(), 3, r.omega);
  r.radius = p.radius[k];
  r.mass = p.mass[k];
  r.material = p.material[k];
  r.body = p.body.size() == p.size() ? p.body[k] : 0;
  r.id = p.id[k];
  return r;
}

// The fields a frame stores, in the records' order.
Particles frame_particles(const std::vector<FrameRecord>& records) {
  Particles q;
  const std::size_t n = records.size();
  q.position.resize(n);
  q.velocity.resize(n);
  q.omega.resize(n);
  q.radius.resize(n);
  q.mass.resize(n);
  q.material.resize(n);
  q.body.resize(n);
  q.id.resize(n);
  for (std::size_t k = 0; k < n; ++k) {
    const FrameRecord& r = records[k];
    q.position[k] = Vec3(r.position[0], r.position[1], r.position[2]);
    q.velocity[k] = Vec3(r.velocity[0], r.velocity[1], r.velocity[2]);
    q.omega[k] = Vec3(r.omega[0], r.omega[1], r.omega[2]);
    q.radius[k] = r.radius;
    q.mass[k] = r.mass;
    q.material[k] = r.material;
    q.body[k] = r.body;
    q.id[k] = r.id;
  }
  return q;
}

// The rank's own particles (not its ghosts) as frame records, in storage order.
std::vector<FrameRecord> own_frame_records(const Particles& p, std::size_t owned) {
  std::vector<FrameRecord> mine;
  mine.reserve(owned);
  for (std::size_t k = 0; k < p.size(); ++k)
    if (!(p.flags[k] & kGhost)) mine.push_back(frame_record_of(p, k));
  return mine;
}

}  // namespace

GatheredFrame DistributedSimulation::gather_frame(int root) const {
  const Simulation& sim = *local_;
  const Particles& p = sim.particles();
  const Bonds& b = sim.bonds();
  std::vector<FrameRecord> mine = own_frame_records(p, owned_);
  // A rank holds the bonds it owns only (owner-computes): each is gathered once. A bond flagged
  // broken but not yet removed is not part of a frame (collect_frame_bonds).
  const bool flags = b.broken.size() == b.size();
  std::vector<std::array<Index, 2>> pairs;
  pairs.reserve(b.size());
  for (std::size_t k = 0; k < b.size(); ++k) {
    if (flags && b.broken[k] != 0) continue;
    const Index x = p.id[static_cast<std::size_t>(b.i[k])], y = p.id[static_cast<std::size_t>(b.j[k])];
    pairs.push_back({std::min(x, y), std::max(x, y)});
  }
  std::vector<FrameRecord> all = gather_to(mine, root, comm_);
  std::vector<std::array<Index, 2>> all_pairs = gather_to(pairs, root, comm_);
  GatheredFrame f;
  if (rank_ != root) return f;

  // Ascending id for the particles, ascending (smaller id, larger id) for the bonds: the file's
  // order does not depend on the partition.
  std::sort(all.begin(), all.end(), [](const FrameRecord& x, const FrameRecord& y) { return x.id < y.id; });
  std::sort(all_pairs.begin(), all_pairs.end());
  f.particles = frame_particles(all);
  const Particles& q = f.particles;
  const auto row_of = [&](Index id) {
    const auto it = std::lower_bound(q.id.begin(), q.id.end(), id);
    if (it == q.id.end() || *it != id)
      throw std::logic_error(fmt::format("gather_frame: particle id {} is held by no rank", id));
    return static_cast<Index>(it - q.id.begin());
  };
  f.bonds.i.resize(all_pairs.size());
  f.bonds.j.resize(all_pairs.size());
  for (std::size_t k = 0; k < all_pairs.size(); ++k) {
    f.bonds.i[k] = row_of(all_pairs[k][0]);
    f.bonds.j[k] = row_of(all_pairs[k][1]);
  }
  return f;
}

FrameShare DistributedSimulation::frame_share() const {
  const Simulation& sim = *local_;
  const Particles& p = sim.particles();
  const Bonds& b = sim.bonds();
  std::vector<FrameRecord> mine = own_frame_records(p, owned_);
  std::sort(mine.begin(), mine.end(), [](const FrameRecord& x, const FrameRecord& y) { return x.id < y.id; });
  const bool flags = b.broken.size() == b.size();
  unsigned long long bonds = 0;
  for (std::size_t k = 0; k < b.size(); ++k) bonds += flags && b.broken[k] != 0 ? 0 : 1;
  const std::vector<RowRange> rows = row_ranges({mine.size(), bonds}, comm_);

  FrameShare f;
  f.first_row = rows[0].first;
  f.total_rows = rows[0].total;
  f.first_bond = rows[1].first;
  f.total_bonds = rows[1].total;
  f.particles = frame_particles(mine);
  const GlobalRows row_of(f.particles.id, f.first_row, halo_->links(), comm_);
  f.bond_rows.reserve(2 * bonds);
  for (std::size_t k = 0; k < b.size(); ++k) {
    if (flags && b.broken[k] != 0) continue;
    const Index x = p.id[static_cast<std::size_t>(b.i[k])], y = p.id[static_cast<std::size_t>(b.j[k])];
    f.bond_rows.push_back(row_of(std::min(x, y)));
    f.bond_rows.push_back(row_of(std::max(x, y)));
  }
  return f;
}

}  // namespace shard::mpi
