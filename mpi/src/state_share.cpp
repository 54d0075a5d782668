// The whole run's state for a checkpoint (the serial layout, docs/how-to/restart-a-run.md), either
// gathered to one rank (gather_state) or as each rank's share of a file every rank writes at once
// (state_share). Both take the same records of a rank's own particles, bonds and touching
// contacts; they differ in where the records go and how a bond's ends become rows.
#include <fmt/format.h>

#include <algorithm>
#include <stdexcept>

#include "comm.hpp"
#include "global_rows.hpp"
#include "records.hpp"
#include "shard/mpi/distributed_simulation.hpp"

namespace shard::mpi {
namespace {

// One rank's own part of the state as records: particles (ascending id), bonds (smaller id,
// larger id, model state) and touching contacts (append_touching's records).
struct OwnRecords {
  std::vector<ParticleRecord> particles;
  std::vector<double> bonds, touching;
  std::size_t bond_width = 2, contact_width = 2;
};

OwnRecords own_records(const Simulation& sim, std::size_t history_stride, bool contacts) {
  OwnRecords r;
  const Particles& p = sim.particles();
  for (std::size_t k = 0; k < p.size(); ++k)
    if (!(p.flags[k] & kGhost)) r.particles.push_back(record_of(p, k));
  std::sort(r.particles.begin(), r.particles.end(), by_id);
  // A rank holds the bonds it owns only (owner-computes): each bond is taken once.
  const Bonds& b = sim.bonds();
  const std::size_t stride = b.stride;
  r.bond_width = 2 + stride;
  for (std::size_t k = 0; k < b.size(); ++k) {
    const Index a = p.id[static_cast<std::size_t>(b.i[k])], c = p.id[static_cast<std::size_t>(b.j[k])];
    r.bonds.push_back(static_cast<double>(std::min(a, c)));
    r.bonds.push_back(static_cast<double>(std::max(a, c)));
    r.bonds.insert(r.bonds.end(), b.state.begin() + static_cast<std::ptrdiff_t>(k * stride),
                   b.state.begin() + static_cast<std::ptrdiff_t>((k + 1) * stride));
  }
  r.contact_width = 2 + history_stride;
  if (contacts) append_touching(sim.export_state(), r.touching);
  return r;
}

// Particles, bonds and touching contacts of `r` into `s`, in ascending record order, each end named
// by `row_of` (a wall's negative index kept).
template <class RowOf>
void fill_from_records(SimulationState& s, const OwnRecords& r, std::size_t bond_stride, const RowOf& row_of) {
  s.particles.reserve(r.particles.size());
  for (const ParticleRecord& x : r.particles) append(s.particles, x, false);
  const std::vector<std::size_t> bond_order = record_order(r.bonds, r.bond_width);
  s.bonds.stride = bond_stride;
  s.bonds.keeps_loads = false;
  s.bonds.resize(bond_order.size());
  for (std::size_t k = 0; k < bond_order.size(); ++k) {
    const double* rec = r.bonds.data() + bond_order[k] * r.bond_width;
    s.bonds.i[k] = row_of(static_cast<Index>(rec[0]));
    s.bonds.j[k] = row_of(static_cast<Index>(rec[1]));
    std::copy_n(rec + 2, bond_stride, s.bonds.state.data() + k * bond_stride);
  }
  NeighbourState& list = s.neighbours;
  for (std::size_t k : record_order(r.touching, r.contact_width)) {
    const double* rec = r.touching.data() + k * r.contact_width;
    list.first.push_back(row_of(static_cast<Index>(rec[0])));
    list.second.push_back(rec[1] < 0 ? static_cast<Index>(rec[1]) : row_of(static_cast<Index>(rec[1])));
    list.history.insert(list.history.end(), rec + 2, rec + r.contact_width);
    list.touching.push_back(1);
  }
}

}  // namespace

// What every rank knows of the whole run alike (collective: the totals are summed in rank order).
void DistributedSimulation::fill_whole_figures(SimulationState& s) const {
  const Simulation& sim = *local_;
  const Energies own = sim.energies();
  std::vector<double> counts{static_cast<double>(sim.contact_count()), own.contact, own.bond};
  for (const Wall& w : sim.walls()) {
    counts.push_back(w.contact_work);
    counts.push_back(static_cast<double>(w.impacts));
  }
  const std::vector<double> total = sum_in_rank_order(counts, comm_);
  std::int64_t rebuilds = sim.neighbour_rebuilds();  // rank 0's count stands for the run's
  MPI_Bcast(&rebuilds, 1, MPI_INT64_T, 0, comm_);
  s.step = sim.step_count();
  s.time = sim.time();
  s.dt = sim.dt();
  s.events = events_;
  s.bonds_broken = bonds_broken();
  s.contacts = static_cast<std::size_t>(total[0]);
  s.contact_energy = total[1];
  s.bond_energy = total[2];
  const std::vector<Wall>& walls = sim.walls();
  for (std::size_t w = 0; w < walls.size(); ++w) {
    const Wall& x = walls[w];
    s.walls.push_back({x.velocity, x.displacement, x.force, x.torque, total[3 + 2 * w], x.stored_energy,
                       static_cast<std::int64_t>(total[4 + 2 * w])});
  }
  s.neighbours.skin = skin_;
  s.neighbours.history_stride = contact_ ? contact_->history_size() : 0;
  s.neighbours.rebuilds = rebuilds;
}

SimulationState DistributedSimulation::gather_state(int root, bool contacts) const {
  const std::size_t history_stride = contact_ ? contact_->history_size() : 0;
  OwnRecords mine = own_records(*local_, history_stride, contacts);
  SimulationState s;
  fill_whole_figures(s);
  OwnRecords all;
  all.bond_width = mine.bond_width;
  all.contact_width = mine.contact_width;
  all.particles = gather_to(mine.particles, root, comm_);
  all.bonds = gather_to(mine.bonds, root, comm_);
  all.touching = gather_to(mine.touching, root, comm_);
  if (rank_ != root) return {};
  std::sort(all.particles.begin(), all.particles.end(), by_id);
  const auto row_of = [&](Index id) {
    const auto it = std::lower_bound(all.particles.begin(), all.particles.end(), id,
                                     [](const ParticleRecord& r, Index v) { return r.id < v; });
    if (it == all.particles.end() || it->id != id)
      throw std::logic_error(fmt::format("gather: particle id {} is held by no rank", id));
    return static_cast<Index>(it - all.particles.begin());
  };
  fill_from_records(s, all, local_->bonds().stride, row_of);
  return s;
}

StateShare DistributedSimulation::state_share(bool contacts) const {
  const std::size_t history_stride = contact_ ? contact_->history_size() : 0;
  const OwnRecords mine = own_records(*local_, history_stride, contacts);
  StateShare share;
  fill_whole_figures(share.state);
  const std::vector<RowRange> rows = row_ranges(
      {mine.particles.size(), mine.bonds.size() / mine.bond_width, mine.touching.size() / mine.contact_width}, comm_);
  share.particles = {rows[0].first, rows[0].total};
  share.bonds = {rows[1].first, rows[1].total};
  share.contacts = {rows[2].first, rows[2].total};
  std::vector<Index> ids;
  ids.reserve(mine.particles.size());
  for (const ParticleRecord& r : mine.particles) ids.push_back(r.id);
  const GlobalRows row_of(std::move(ids), share.particles.first, halo_->links(), comm_);
  fill_from_records(share.state, mine, local_->bonds().stride, row_of);
  return share;
}

}  // namespace shard::mpi
