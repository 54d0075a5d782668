// A re-partition in place (docs/explanation/scaling.md, "How the world is cut"). The rank's state
// leaves its Simulation without a copy (take_state); the particles whose cell now belongs to
// another rank leave with the bonds and touching contacts they own; the ones that stay keep their
// order, closed up over the gaps; the arrivals (ascending id) and the new ghost layer (ascending
// id) are appended; the state moves back. The local order is a function of the run's state and
// the rank count alone, so a run stays bit-reproducible on a given rank count.
#include <fmt/format.h>

#include <time.h>

#include <algorithm>
#include <limits>
#include <stdexcept>
#include <unordered_map>
#include <utility>

#include "comm.hpp"
#include "routing.hpp"
#include "shard/checkpoint.hpp"
#include "shard/mpi/distributed_simulation.hpp"
#include "shard/particle_arrays.hpp"

namespace shard::mpi {
namespace {

// The end of bond k that owns it: the one with the smaller stable id.
std::size_t owning_end(const Particles& p, const Bonds& bonds, std::size_t k) {
  const auto i = static_cast<std::size_t>(bonds.i[k]), j = static_cast<std::size_t>(bonds.j[k]);
  return p.id[i] < p.id[j] ? i : j;
}

double thread_cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

bool is_ghost(const Particles& p, std::size_t k) { return (p.flags[k] & kGhost) != 0; }

// The lower corner of the owned particles, and the longest bond (its far end may be a ghost).
std::pair<Vec3, double> extent(const SimulationState& s) {
  const Particles& p = s.particles;
  Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity());
  for (std::size_t k = 0; k < p.size(); ++k)
    if (!is_ghost(p, k)) lo = lo.cwiseMin(p.position[k]);
  double longest = 0;
  for (std::size_t b = 0; b < s.bonds.size(); ++b)
    longest = std::max(longest, (p.position[static_cast<std::size_t>(s.bonds.i[b])] -
                                 p.position[static_cast<std::size_t>(s.bonds.j[b])]).norm());
  return {lo, longest};
}

// Where each local particle is: its cell and, once the partition is known, its new owner (-1 for
// a ghost, which belongs to no one here).
struct Placement {
  std::vector<std::uint64_t> cell;
  std::vector<int> owner;
};

// Each owned particle's cell and the cost of the cell: itself, the bonds and touching contacts it
// owns (the first partition's measure: cell_costs in distributed_simulation.cpp).
std::vector<CellCost> owned_cells(const SimulationState& s, const CellGrid& grid, Placement& at) {
  const Particles& p = s.particles;
  std::vector<double> cost(p.size(), 1.0);
  for (std::size_t b = 0; b < s.bonds.size(); ++b) cost[owning_end(p, s.bonds, b)] += 1;
  const NeighbourState& list = s.neighbours;
  for (std::size_t k = 0; k < list.first.size(); ++k)
    if (list.touching[k]) cost[static_cast<std::size_t>(list.first[k])] += 1;
  at.cell.assign(p.size(), 0);
  at.owner.assign(p.size(), -1);
  std::vector<CellCost> cells;
  cells.reserve(p.size());
  for (std::size_t k = 0; k < p.size(); ++k) {
    if (is_ghost(p, k)) continue;
    at.cell[k] = grid.key(p.position[k]);
    cells.push_back({at.cell[k], cost[k]});
  }
  return cells;
}

// What leaves: each owned particle whose new owner is another rank, with the bonds and touching
// contacts it owns; and the ghost copy of every owned particle for the ranks around its cell.
// Fills each owned particle's new owner into `at`.
Outgoing departures(const SimulationState& s, const Partition& partition, int self, std::size_t ranks,
                    Placement& at) {
  const Particles& p = s.particles;
  Outgoing out(ranks);
  RanksAround around(partition);
  for (std::size_t k = 0; k < p.size(); ++k) {
    if (is_ghost(p, k)) continue;
    const int owner = partition.owner_of(at.cell[k]);
    at.owner[k] = owner;
    const std::vector<int>& near = around.of(at.cell[k], owner);
    if (owner == self && near.empty()) continue;
    ParticleRecord r = record_of(p, k);
    r.owner = owner;
    if (owner != self) out.to_owner[static_cast<std::size_t>(owner)].push_back(r);
    for (int d : near) out.to_ghost[static_cast<std::size_t>(d)].push_back(r);
  }
  const Bonds& bonds = s.bonds;
  for (std::size_t b = 0; b < bonds.size(); ++b) {
    const int owner = at.owner[owning_end(p, bonds, b)];
    if (owner == self) continue;
    std::vector<double>& to = out.bonds_to[static_cast<std::size_t>(owner)];
    const Index a = p.id[static_cast<std::size_t>(bonds.i[b])], c = p.id[static_cast<std::size_t>(bonds.j[b])];
    to.push_back(static_cast<double>(std::min(a, c)));
    to.push_back(static_cast<double>(std::max(a, c)));
    to.insert(to.end(), bonds.state.begin() + static_cast<std::ptrdiff_t>(b * bonds.stride),
              bonds.state.begin() + static_cast<std::ptrdiff_t>((b + 1) * bonds.stride));
  }
  const NeighbourState& list = s.neighbours;
  const std::size_t h = list.history_stride;
  for (std::size_t k = 0; k < list.first.size(); ++k) {
    const auto first = static_cast<std::size_t>(list.first[k]);
    if (!list.touching[k] || at.owner[first] == self) continue;
    if (at.owner[first] < 0)
      throw std::logic_error(fmt::format("partition: a touching pair's first particle (id {}) is a ghost", p.id[first]));
    std::vector<double>& to = out.contacts_to[static_cast<std::size_t>(at.owner[first])];
    const Index second = list.second[k];
    to.push_back(static_cast<double>(p.id[first]));
    to.push_back(second < 0 ? static_cast<double>(second) : static_cast<double>(p.id[static_cast<std::size_t>(second)]));
    to.insert(to.end(), list.history.begin() + static_cast<std::ptrdiff_t>(k * h),
              list.history.begin() + static_cast<std::ptrdiff_t>((k + 1) * h));
  }
  return out;
}

// The local indices after the re-partition: the particles that stay here keep their order; the
// arrivals (ascending id) are merged in by id when the staying ones are in ascending id (the order
// of the first partition, which the kernel keeps below its renumbering size), appended otherwise;
// the new ghosts (ascending id) follow. `of_old(k)` for the particle at old index k (-1 when no
// longer held), `of_id` for a particle named by an arrived bond or contact.
class Renumbering {
 public:
  // `bond_width`, `contact_width`: the doubles of an arrived bond's and contact's record.
  Renumbering(const Particles& p, const Placement& at, int self, const Arrived& in, std::size_t bond_width,
              std::size_t contact_width)
      : in_(in) {
    stays_.assign(p.size(), 0);
    bool ascending = true;
    for (std::size_t k = 0; k < p.size(); ++k) {
      if (at.owner[k] != self) continue;
      ascending = ascending && (staying_ == 0 || p.id[k] > p.id[staying_last_]);
      stays_[k] = 1;
      staying_last_ = k;
      ++staying_;
    }
    place_arrivals(p, ascending);
    for (std::size_t k = 0; k < p.size(); ++k)
      if (!stays_[k]) of_old_[k] = of_new(p.id[k]);
    name_staying(p, bond_width, contact_width);
  }
  std::size_t staying() const { return staying_; }
  std::size_t owned() const { return staying_ + in_.mine.size(); }
  Index of_old(Index k) const { return of_old_[static_cast<std::size_t>(k)]; }
  bool stays(std::size_t k) const { return stays_[k] != 0; }
  Index of_id(Index id) const {
    const Index k = of_new(id);
    if (k >= 0) return k;
    const auto it = named_.find(id);
    return it != named_.end() ? it->second : Index{-1};
  }
  Index arrival_at(std::size_t m) const { return arrival_at_[m]; }
  // A per-particle array with the staying particles' entries at their new places (closed up over
  // the gaps, then spread from the back over the arrivals' slots) and room for the arrivals and
  // `ghosts` new ghosts, in place.
  template <class T>
  void place(std::vector<T>& v, std::size_t ghosts) const {
    std::size_t s = 0;
    for (std::size_t k = 0; k < v.size(); ++k)
      if (stays_[k]) {
        if (s != k) v[s] = std::move(v[k]);
        ++s;
      }
    v.resize(owned() + ghosts);
    for (std::size_t t = staying_; t-- > 0;)
      if (static_cast<std::size_t>(staying_at_[t]) != t) v[static_cast<std::size_t>(staying_at_[t])] = std::move(v[t]);
  }

 private:
  // The new index of each staying particle and each arrival: merged by id or the arrivals after.
  void place_arrivals(const Particles& p, bool merge) {
    of_old_.assign(p.size(), -1);
    staying_at_.resize(staying_);
    arrival_at_.resize(in_.mine.size());
    std::size_t s = 0, m = 0, next = 0;
    for (std::size_t k = 0; k < p.size(); ++k) {
      if (!stays_[k]) continue;
      for (; merge && m < in_.mine.size() && in_.mine[m].id < p.id[k]; ++m) arrival_at_[m] = static_cast<Index>(next++);
      staying_at_[s++] = static_cast<Index>(next);
      of_old_[k] = static_cast<Index>(next++);
    }
    for (; m < in_.mine.size(); ++m) arrival_at_[m] = static_cast<Index>(next++);
  }
  // An arrival's or new ghost's index.
  Index of_new(Index id) const {
    const Index m = find_record(in_.mine, id);
    if (m >= 0) return arrival_at_[static_cast<std::size_t>(m)];
    const Index g = find_record(in_.ghosts, id);
    return g >= 0 ? static_cast<Index>(owned()) + g : Index{-1};
  }
  // The staying particles that arrived bonds and contacts name (their far ends), found in one pass.
  void name_staying(const Particles& p, std::size_t bond_width, std::size_t contact_width) {
    const auto ask = [&](const std::vector<double>& records, std::size_t width) {
      for (std::size_t r = 0; r + width <= records.size(); r += width)
        for (std::size_t e = 0; e < 2; ++e)
          if (records[r + e] >= 0 && of_new(static_cast<Index>(records[r + e])) < 0)
            named_.emplace(static_cast<Index>(records[r + e]), -1);
    };
    ask(in_.bonds, bond_width);
    ask(in_.contacts, contact_width);
    if (named_.empty()) return;
    for (std::size_t k = 0; k < p.size(); ++k)
      if (stays_[k])
        if (const auto it = named_.find(p.id[k]); it != named_.end()) it->second = of_old_[k];
  }

  const Arrived& in_;
  std::vector<std::uint8_t> stays_;
  std::vector<Index> of_old_, staying_at_, arrival_at_;
  std::size_t staying_ = 0, staying_last_ = 0;
  std::unordered_map<Index, Index> named_;
};

Index held(Index k, Index id, int rank, const char* what) {
  if (k < 0)
    throw std::logic_error(
        fmt::format("partition: the {} end id {} is not within the ghost layer of rank {}", what, id, rank));
  return k;
}

// Bond record `rec` (smaller id, larger id, state) into slot b, the smaller id's end first.
void write_bond(Bonds& bonds, std::size_t b, const double* rec, const Renumbering& at, int rank) {
  bonds.i[b] = held(at.of_id(static_cast<Index>(rec[0])), static_cast<Index>(rec[0]), rank, "bond's");
  bonds.j[b] = held(at.of_id(static_cast<Index>(rec[1])), static_cast<Index>(rec[1]), rank, "bond's");
  std::copy_n(rec + 2, bonds.stride, bonds.state.begin() + static_cast<std::ptrdiff_t>(b * bonds.stride));
}

// Room for `front` new bonds before the others and `back` after them (zero loads, not broken).
void open_bonds(Bonds& bonds, std::size_t front, std::size_t back) {
  const auto open = [&](auto& v, std::size_t per, const auto& fill) {
    v.insert(v.begin(), front * per, fill);
    v.resize(v.size() + back * per, fill);
  };
  open(bonds.i, 1, Index{0});
  open(bonds.j, 1, Index{0});
  open(bonds.state, bonds.stride, 0.0);
  if (bonds.keeps_loads) {
    open(bonds.force, 1, Vec3::Zero().eval());
    open(bonds.torque_i, 1, Vec3::Zero().eval());
    open(bonds.torque_j, 1, Vec3::Zero().eval());
    open(bonds.energy, 1, 0.0);
  }
  open(bonds.broken, 1, std::uint8_t{0});
  open(bonds.stress, 1, BondStress{});
}

// The bonds: those that left dropped (the kernel's compaction of broken bonds, order kept), the
// others' ends renamed, the arrivals' set in in the order of the first partition's exchange: those
// from lower ranks before the staying ones, those from higher ranks after.
void settle_bonds(Bonds& bonds, const Particles& p, const Renumbering& at, const Arrived& in, int rank) {
  for (std::size_t b = 0; b < bonds.size(); ++b) bonds.broken[b] = at.stays(owning_end(p, bonds, b)) ? 0 : 1;
  bonds.remove_broken();
  for (std::size_t b = 0; b < bonds.size(); ++b) {
    bonds.i[b] = held(at.of_old(bonds.i[b]), p.id[static_cast<std::size_t>(bonds.i[b])], rank, "bond's");
    bonds.j[b] = held(at.of_old(bonds.j[b]), p.id[static_cast<std::size_t>(bonds.j[b])], rank, "bond's");
  }
  const std::size_t width = 2 + bonds.stride, kept = bonds.size();
  std::size_t lower = 0;
  for (int r = 0; r < rank; ++r) lower += in.bonds_from[static_cast<std::size_t>(r)];
  const std::size_t front = lower / width, back = in.bonds.size() / width - front;
  open_bonds(bonds, front, back);
  for (std::size_t r = 0; r < front + back; ++r)
    write_bond(bonds, r < front ? r : kept + r, in.bonds.data() + r * width, at, rank);
}

// The touching contacts: those whose first particle stays, their ends renamed (order kept), then the
// arrivals; every one touches. Without build positions the next force pass rebuilds the list,
// which carries each pair's history over.
void settle_contacts(NeighbourState& list, const Particles& p, const Renumbering& at, const std::vector<double>& arrived,
                     int rank) {
  const std::size_t h = list.history_stride;
  std::size_t kept = 0;
  for (std::size_t k = 0; k < list.first.size(); ++k) {
    if (!list.touching[k] || !at.stays(static_cast<std::size_t>(list.first[k]))) continue;
    const Index second = list.second[k];
    list.first[kept] = at.of_old(list.first[k]);
    list.second[kept] =
        second < 0 ? second : held(at.of_old(second), p.id[static_cast<std::size_t>(second)], rank, "contact's");
    if (kept != k)
      std::copy_n(list.history.begin() + static_cast<std::ptrdiff_t>(k * h), h,
                  list.history.begin() + static_cast<std::ptrdiff_t>(kept * h));
    ++kept;
  }
  list.first.resize(kept);
  list.second.resize(kept);
  list.history.resize(kept * h);
  const std::size_t width = 2 + h;
  for (std::size_t r = 0; r < arrived.size() / width; ++r) {
    const double* rec = arrived.data() + r * width;
    list.first.push_back(held(at.of_id(static_cast<Index>(rec[0])), static_cast<Index>(rec[0]), rank, "contact's"));
    list.second.push_back(rec[1] < 0 ? static_cast<Index>(rec[1])
                                     : held(at.of_id(static_cast<Index>(rec[1])), static_cast<Index>(rec[1]), rank,
                                            "contact's"));
    list.history.insert(list.history.end(), rec + 2, rec + width);
  }
  list.touching.assign(list.first.size(), 1);
  list.position_at_build.clear();
}

// The particles: the staying ones in place (Renumbering::place), the arrivals and new ghosts written.
void settle_particles(Particles& p, const Renumbering& at, const Arrived& in) {
  const std::size_t g = in.ghosts.size();
  for_each_particle_array([&](auto& v) { at.place(v, g); }, p);
  for (std::size_t m = 0; m < in.mine.size(); ++m) write(p, static_cast<std::size_t>(at.arrival_at(m)), in.mine[m], false);
  for (std::size_t k = 0; k < g; ++k) write(p, at.owned() + k, in.ghosts[k], true);
}

// The new partition and what it sends where; a rank's state is not touched yet.
struct Cut {
  CellGrid grid;
  Partition partition;
  Placement at;
};

Cut cut_anew(const SimulationState& s, double r_max, double skin, int ranks, MPI_Comm comm) {
  Cut c;
  const auto [lo, longest] = extent(s);
  c.grid = partition_grid(lo, r_max, longest, skin, comm);
  c.partition = Partition::balance(all_gather(owned_cells(s, c.grid, c.at), comm), ranks, c.grid.cell);
  return c;
}

DistributedSimulation::Migration counted(const Outgoing& out, std::size_t bond_width, std::size_t contact_width) {
  DistributedSimulation::Migration m;
  for (std::size_t r = 0; r < out.to_owner.size(); ++r) {
    m.particles += out.to_owner[r].size();
    m.bonds += out.bonds_to[r].size() / bond_width;
    m.contacts += out.contacts_to[r].size() / contact_width;
  }
  return m;
}

}  // namespace

void DistributedSimulation::repartition() {
  const double start = MPI_Wtime(), cpu_start = thread_cpu_seconds();
  SimulationState s = local_->take_state();
  Cut cut;
  try {
    cut = cut_anew(s, r_max_, skin_, ranks_, comm_);
  } catch (...) {
    local_->import_state(std::move(s));  // a particle outside the grid, named by the message
    throw;
  }
  const auto R = static_cast<std::size_t>(ranks_);
  Arrived in;
  {
    const Outgoing out = departures(s, cut.partition, rank_, R, cut.at);
    last_migration_ = counted(out, 2 + s.bonds.stride, 2 + s.neighbours.history_stride);
    migration_total_.particles += last_migration_.particles;
    migration_total_.bonds += last_migration_.bonds;
    migration_total_.contacts += last_migration_.contacts;
    in = exchange(out, comm_);
  }
  const Renumbering renumber(s.particles, cut.at, rank_, in, 2 + s.bonds.stride, 2 + s.neighbours.history_stride);
  std::vector<std::pair<Index, std::uint64_t>> cells;
  cells.reserve(renumber.staying() + in.mine.size());
  for (std::size_t k = 0; k < s.particles.size(); ++k)
    if (renumber.stays(k)) cells.emplace_back(s.particles.id[k], cut.at.cell[k]);
  for (const ParticleRecord& r : in.mine)
    cells.emplace_back(r.id, cut.grid.key(Vec3(r.position[0], r.position[1], r.position[2])));
  halo_->reset(halo_links(cells, in.ghosts, cut.partition, rank_, R));
  settle_bonds(s.bonds, s.particles, renumber, in, rank_);
  settle_contacts(s.neighbours, s.particles, renumber, in.contacts, rank_);
  settle_particles(s.particles, renumber, in);
  owned_ = renumber.owned();
  local_->import_state(std::move(s));
  position_at_partition_ = local_->particles().position;
  partition_id_ = local_->particles().id;
  ++repartitions_;
  partition_seconds_ += MPI_Wtime() - start;
  repartition_cpu_seconds_ += thread_cpu_seconds() - cpu_start;
}

}  // namespace shard::mpi
