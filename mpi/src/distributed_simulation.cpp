#include "shard/mpi/distributed_simulation.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <utility>

#include "comm.hpp"
#include "halo.hpp"
#include "partition.hpp"
#include "records.hpp"
#include "routing.hpp"
#include "shard/checkpoint.hpp"

namespace shard::mpi {
namespace {

// Re-partition before some particle can have moved half the skin since the last partition by the
// end of the next step (its travel so far plus twice the largest |v| dt, a margin for the next
// drift). Two particles that touch before then were at most 2 r_max + skin apart at the partition,
// in neighbouring cells: the ghost layer (the 26 cells around each owned one) holds every particle
// an owned one can touch. The serial run rebuilds its list at the same travel (half the skin).
constexpr double kStepMargin = 2;

// The slot of particle `id` in `sorted` (ascending id); the id must be there.
std::size_t slot_of(const std::vector<ParticleRecord>& sorted, Index id) {
  const auto it = std::lower_bound(sorted.begin(), sorted.end(), id,
                                   [](const ParticleRecord& r, Index v) { return r.id < v; });
  if (it == sorted.end() || it->id != id)
    throw std::logic_error(fmt::format("partition: particle id {} is not owned here", id));
  return static_cast<std::size_t>(it - sorted.begin());
}

// Flat records of one kind (bonds or contacts): each `size` values, the first the id of the
// particle whose owner keeps it.
struct FlatRecords {
  const std::vector<double>& values;
  std::size_t size;
  std::size_t count() const { return values.size() / size; }
  const double* operator[](std::size_t k) const { return values.data() + k * size; }
  Index first_id(std::size_t k) const { return static_cast<Index>(values[k * size]); }
};

// The lower corner of the records' positions (+infinity without any).
Vec3 lowest(const std::vector<ParticleRecord>& particles) {
  Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity());
  for (const ParticleRecord& r : particles) lo = lo.cwiseMin(Vec3(r.position[0], r.position[1], r.position[2]));
  return lo;
}

// Cost of each owned particle's cell: itself, the bonds and contacts it owns; `key` gets each
// particle's cell.
std::vector<CellCost> cell_costs(const std::vector<ParticleRecord>& particles, const FlatRecords& bonds,
                                 const FlatRecords& contacts, const CellGrid& grid, std::vector<std::uint64_t>& key) {
  std::vector<double> cost(particles.size(), 1.0);
  for (std::size_t b = 0; b < bonds.count(); ++b) cost[slot_of(particles, bonds.first_id(b))] += 1;
  for (std::size_t c = 0; c < contacts.count(); ++c) cost[slot_of(particles, contacts.first_id(c))] += 1;
  key.resize(particles.size());
  std::vector<CellCost> cells;
  for (std::size_t k = 0; k < particles.size(); ++k) {
    const ParticleRecord& r = particles[k];
    key[k] = grid.key(Vec3(r.position[0], r.position[1], r.position[2]));
    cells.push_back({key[k], cost[k]});
  }
  return cells;
}

Outgoing route(const std::vector<ParticleRecord>& particles, const FlatRecords& bonds, const FlatRecords& contacts,
               const Partition& partition, const std::vector<std::uint64_t>& key, std::size_t ranks) {
  Outgoing out(ranks);
  RanksAround around(partition);
  std::vector<int> owner(particles.size());
  for (std::size_t k = 0; k < particles.size(); ++k) {
    ParticleRecord r = particles[k];
    r.owner = partition.owner_of(key[k]);
    owner[k] = r.owner;
    out.to_owner[static_cast<std::size_t>(r.owner)].push_back(r);
    for (int d : around.of(key[k], r.owner)) out.to_ghost[static_cast<std::size_t>(d)].push_back(r);
  }
  const auto send = [&](const FlatRecords& records, std::vector<std::vector<double>>& to) {
    for (std::size_t b = 0; b < records.count(); ++b) {
      auto& dest = to[static_cast<std::size_t>(owner[slot_of(particles, records.first_id(b))])];
      dest.insert(dest.end(), records[b], records[b] + records.size);
    }
  };
  send(bonds, out.bonds_to);
  send(contacts, out.contacts_to);
  return out;
}

// The local index of particle `id` (owned ones first, then the ghosts); -1 when not held here.
Index local_index(const Arrived& in, Index id) {
  const Index o = find_record(in.mine, id);
  if (o >= 0) return o;
  const Index g = find_record(in.ghosts, id);
  return g >= 0 ? static_cast<Index>(in.mine.size()) + g : Index{-1};
}

// This rank's particles: owned ones first, then the ghosts, each in ascending id.
Particles local_particles(const Arrived& in) {
  Particles local;
  local.reserve(in.mine.size() + in.ghosts.size());
  for (const ParticleRecord& r : in.mine) append(local, r, false);
  for (const ParticleRecord& r : in.ghosts) append(local, r, true);
  return local;
}

// The received bonds' ends and touching contacts in local indices.
struct LocalLinks {
  std::vector<std::pair<Index, Index>> bond_ends;
  NeighbourState touching;
};

// Bonds and contacts in local indices; a far end not held here would be a gap in the ghost layer.
LocalLinks local_links(const Arrived& in, std::size_t bond_stride, std::size_t history_stride, double skin, int rank) {
  const auto held = [&](double id, const char* what) {
    const Index k = local_index(in, static_cast<Index>(id));
    if (k < 0)
      throw std::logic_error(fmt::format("partition: the {} end id {} is not within the ghost layer of rank {}", what,
                                         static_cast<Index>(id), rank));
    return k;
  };
  LocalLinks out;
  for (std::size_t b = 0; b < in.bonds.size() / (2 + bond_stride); ++b) {
    const double* rec = in.bonds.data() + b * (2 + bond_stride);
    out.bond_ends.emplace_back(held(rec[0], "bond's"), held(rec[1], "bond's"));
  }
  NeighbourState& touching = out.touching;
  touching.skin = skin;
  touching.history_stride = history_stride;
  for (std::size_t c = 0; c < in.contacts.size() / (2 + history_stride); ++c) {
    const double* rec = in.contacts.data() + c * (2 + history_stride);
    touching.first.push_back(held(rec[0], "contact's"));
    touching.second.push_back(rec[1] < 0 ? static_cast<Index>(rec[1]) : held(rec[1], "contact's"));
    touching.history.insert(touching.history.end(), rec + 2, rec + 2 + history_stride);
    touching.touching.push_back(1);
  }
  return out;
}


// The kernel renumbers its particles at its own rebuilds (Morton order): the positions at the
// partition follow their particles by id.
void follow_by_id(const Particles& p, std::vector<Index>& partition_id, std::vector<Vec3>& position_at_partition) {
  if (std::equal(p.id.begin(), p.id.end(), partition_id.begin(), partition_id.end())) return;
  std::vector<std::pair<Index, Vec3>> at(partition_id.size());
  for (std::size_t k = 0; k < at.size(); ++k) at[k] = {partition_id[k], position_at_partition[k]};
  std::sort(at.begin(), at.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  for (std::size_t k = 0; k < p.size(); ++k) {
    const auto it = std::lower_bound(at.begin(), at.end(), p.id[k], [](const auto& a, Index id) { return a.first < id; });
    position_at_partition[k] = it->second;
  }
  partition_id = p.id;
}

// This rank's figures of the step, gathered from every rank: the bonds broken, how far the owned
// particles may have travelled since the partition by the end of the next step, the wall contacts
// begun, and per wall its force, torque and stored energy (7 values).
std::vector<double> step_figures(std::size_t broken, const Particles& p, const std::vector<Vec3>& position_at_partition,
                                 double dt, std::size_t begun, const std::vector<Wall>& walls) {
  double moved = 0, speed = 0;
  for (std::size_t k = 0; k < p.size(); ++k) {
    if (p.flags[k] & kGhost) continue;
    moved = std::max(moved, (p.position[k] - position_at_partition[k]).squaredNorm());
    speed = std::max(speed, p.velocity[k].squaredNorm());
  }
  std::vector<double> mine{static_cast<double>(broken), std::sqrt(moved) + kStepMargin * std::sqrt(speed) * dt,
                           static_cast<double>(begun)};
  for (const Wall& w : walls) {
    mine.insert(mine.end(), w.force.data(), w.force.data() + 3);
    mine.insert(mine.end(), w.torque.data(), w.torque.data() + 3);
    mine.push_back(w.stored_energy);
  }
  return mine;
}

struct StepTotals {
  double events = 0, max_moved = 0, begun = 0;
};

// The gathered figures (`per` values a rank) summed in rank order; the walls' loads become the sums.
StepTotals add_up_ranks(const std::vector<double>& all, std::size_t per, int ranks, std::vector<Wall>& walls) {
  StepTotals t;
  for (auto& w : walls) {
    w.force.setZero();
    w.torque.setZero();
    w.stored_energy = 0;
  }
  for (int r = 0; r < ranks; ++r) {
    const double* v = all.data() + static_cast<std::size_t>(r) * per;
    t.events += v[0];
    t.max_moved = std::max(t.max_moved, v[1]);
    t.begun += v[2];
    for (std::size_t w = 0; w < walls.size(); ++w) {
      const double* x = v + 3 + 7 * w;
      walls[w].force += Vec3(x[0], x[1], x[2]);
      walls[w].torque += Vec3(x[3], x[4], x[5]);
      walls[w].stored_energy += x[6];
    }
  }
  return t;
}

// Every rank's new break events, in the one order all ranks agree on, appended to `events`.
void gather_break_events(const std::vector<BondBreakEvent>& fresh, MPI_Comm comm, std::vector<BondBreakEvent>& events) {
  std::vector<EventRecord> records;
  for (const BondBreakEvent& e : fresh) {
    EventRecord r{};
    r.step = e.step;
    r.time = e.time;
    r.id_i = std::min(e.id_i, e.id_j);
    r.id_j = std::max(e.id_i, e.id_j);
    std::copy_n(e.midpoint.data(), 3, r.midpoint);
    r.stress = e.stress;
    records.push_back(r);
  }
  std::vector<EventRecord> gathered = all_gather(records, comm);
  std::sort(gathered.begin(), gathered.end(), event_order);
  for (const EventRecord& r : gathered) {
    BondBreakEvent e;
    e.step = r.step;
    e.time = r.time;
    e.id_i = r.id_i;
    e.id_j = r.id_j;
    e.midpoint = Vec3(r.midpoint[0], r.midpoint[1], r.midpoint[2]);
    e.stress = r.stress;
    events.push_back(e);
  }
}
}  // namespace

// This rank's particles, bonds and touching contacts before a partition, by stable id.
struct DistributedSimulation::Owned {
  std::vector<ParticleRecord> particles;
  std::size_t bond_stride = 0, history_stride = 0;
  std::vector<double> bonds;     // smaller id, larger id, model state (bond_stride)
  std::vector<double> contacts;  // first id, second id (or -1 - wall), history (history_stride)
};

// What both constructors share: the rank, the largest radius and the skin of `p`, the halo.
void DistributedSimulation::start(const SimulationSetup& setup) {
  rank_ = rank_of(comm_);
  ranks_ = size_of(comm_);
  skin_ = setup.skin > 0 ? setup.skin : 0.2 * std::max(r_max_, 1e-12);  // Simulation's default
  gravity_ = setup.gravity;
  halo_ = std::make_unique<Halo>(comm_);
}

// Particles [begin, end) of `setup` and the bonds whose smaller-id end is among them, as records,
// and the longest of those bonds.
double DistributedSimulation::take_rows(const SimulationSetup& setup, std::size_t begin, std::size_t end,
                                        Owned& owned) const {
  const Particles& p = setup.particles;
  const std::size_t n = p.size();
  // A new bond has no state to send: the bond model initialises it on the rank it lands on.
  owned.bond_stride = 0;
  owned.history_stride = contact_ ? contact_->history_size() : 0;
  for (std::size_t k = begin; k < end; ++k) owned.particles.push_back(record_of(p, k));
  std::vector<std::pair<Index, Index>> bonds;
  double longest = 0;
  for (const auto& [a, b] : setup.bonds) {
    if (a < 0 || b < 0 || static_cast<std::size_t>(a) >= n || static_cast<std::size_t>(b) >= n || a == b)
      throw std::invalid_argument(fmt::format("bond ({}, {}) names a particle that does not exist", a, b));
    const auto first = static_cast<std::size_t>(p.id[static_cast<std::size_t>(a)] < p.id[static_cast<std::size_t>(b)] ? a : b);
    if (first < begin || first >= end) continue;
    bonds.emplace_back(std::min(p.id[static_cast<std::size_t>(a)], p.id[static_cast<std::size_t>(b)]),
                       std::max(p.id[static_cast<std::size_t>(a)], p.id[static_cast<std::size_t>(b)]));
    longest = std::max(longest, (p.position[static_cast<std::size_t>(a)] - p.position[static_cast<std::size_t>(b)]).norm());
  }
  std::sort(bonds.begin(), bonds.end());
  bonds.erase(std::unique(bonds.begin(), bonds.end()), bonds.end());
  for (const auto& [a, b] : bonds) {
    owned.bonds.push_back(a);
    owned.bonds.push_back(b);
  }
  return longest;
}

// The largest radius over every rank's particles of `setup`; refuses a scene without particles.
void DistributedSimulation::find_largest_radius(const Particles& p) {
  for (std::size_t k = 0; k < p.size(); ++k) r_max_ = std::max(r_max_, p.radius[k]);
  r_max_ = max_over_ranks(r_max_, comm_);
  if (!(max_over_ranks(static_cast<double>(p.size()), comm_) > 0))
    throw std::invalid_argument("a decomposed run needs particles");
}

DistributedSimulation::DistributedSimulation(MPI_Comm comm, SimulationSetup setup)
    : comm_(comm), contact_(setup.contact), bond_(setup.bond) {
  find_largest_radius(setup.particles);
  start(setup);
  // Before the first partition every rank takes an equal slice of the scene's listing.
  const std::size_t n = setup.particles.size();
  const std::size_t begin = n * static_cast<std::size_t>(rank_) / static_cast<std::size_t>(ranks_);
  const std::size_t end = n * static_cast<std::size_t>(rank_ + 1) / static_cast<std::size_t>(ranks_);
  Owned owned;
  const double longest = take_rows(setup, begin, end, owned);
  distribute(std::move(owned), longest, setup);
}

DistributedSimulation::DistributedSimulation(MPI_Comm comm, SimulationSetup share, ScatteredScene)
    : comm_(comm), contact_(share.contact), bond_(share.bond) {
  find_largest_radius(share.particles);
  start(share);
  // Each rank holds its share (rank 0 the whole scene, say): the first partition sends it on.
  Owned owned;
  const double longest = take_rows(share, 0, share.particles.size(), owned);
  distribute(std::move(owned), longest, share);
}

DistributedSimulation::DistributedSimulation(MPI_Comm comm, SimulationSetup setup, const SimulationState& from)
    : comm_(comm), contact_(setup.contact), bond_(setup.bond) {
  const Particles& p = from.particles;
  const std::size_t n = p.size();
  if (n == 0) throw std::invalid_argument("the state to continue from holds no particles");
  if (p.id.size() != n) throw std::invalid_argument("the state to continue from holds no particle ids");
  {
    std::vector<Index> ids = p.id;
    std::sort(ids.begin(), ids.end());
    const auto twice = std::adjacent_find(ids.begin(), ids.end());
    if (twice != ids.end())
      throw std::invalid_argument(fmt::format("the state to continue from names particle id {} twice: the ranks "
                                              "place particles by id, which must be unique",
                                              *twice));
  }
  for (std::size_t k = 0; k < n; ++k) r_max_ = std::max(r_max_, p.radius[k]);
  start(setup);
  Owned owned;
  owned.bond_stride = bond_ ? bond_->state_size() : 0;
  owned.history_stride = contact_ ? contact_->history_size() : 0;
  if (from.bonds.size() > 0 && from.bonds.stride != owned.bond_stride)
    throw std::invalid_argument(fmt::format("the state holds {} values per bond, the bond model {}: continue with "
                                            "the bond model the run was started with",
                                            from.bonds.stride, owned.bond_stride));
  if (!from.neighbours.first.empty() && from.neighbours.history_stride != owned.history_stride)
    throw std::invalid_argument(fmt::format("the state holds {} history values per contact, the contact model {}: "
                                            "continue with the contact model the run was started with",
                                            from.neighbours.history_stride, owned.history_stride));
  // Every rank keeps an equal slice of the state's listing; the first partition then places it.
  const std::size_t begin = n * static_cast<std::size_t>(rank_) / static_cast<std::size_t>(ranks_);
  const std::size_t end = n * static_cast<std::size_t>(rank_ + 1) / static_cast<std::size_t>(ranks_);
  const auto in_slice = [&](std::size_t k) { return k >= begin && k < end; };
  for (std::size_t k = begin; k < end; ++k) owned.particles.push_back(record_of(p, k));
  double longest = 0;
  for (std::size_t b = 0; b < from.bonds.size(); ++b) {
    const auto i = static_cast<std::size_t>(from.bonds.i[b]), j = static_cast<std::size_t>(from.bonds.j[b]);
    if (i >= n || j >= n || i == j)
      throw std::invalid_argument(fmt::format("the state's bond {} names a particle that does not exist", b));
    longest = std::max(longest, (p.position[i] - p.position[j]).norm());
    if (!in_slice(p.id[i] < p.id[j] ? i : j)) continue;
    owned.bonds.push_back(static_cast<double>(std::min(p.id[i], p.id[j])));
    owned.bonds.push_back(static_cast<double>(std::max(p.id[i], p.id[j])));
    owned.bonds.insert(owned.bonds.end(), from.bonds.state.begin() + static_cast<std::ptrdiff_t>(b * from.bonds.stride),
                       from.bonds.state.begin() + static_cast<std::ptrdiff_t>((b + 1) * from.bonds.stride));
  }
  const NeighbourState& list = from.neighbours;
  const bool flags_kept = list.touching.size() == list.first.size();
  for (std::size_t k = 0; k < list.first.size(); ++k) {
    const auto a = static_cast<std::size_t>(list.first[k]);
    bool touching = flags_kept && list.touching[k];
    if (!flags_kept)  // checkpoints before the flags were kept: a pair with a history has touched
      for (std::size_t q = 0; q < list.history_stride; ++q) touching = touching || list.history[k * list.history_stride + q] != 0.0;
    if (!touching || a >= n || !in_slice(a)) continue;
    const Index b = list.second[k];
    if (b >= 0 && static_cast<std::size_t>(b) >= n) continue;
    owned.contacts.push_back(static_cast<double>(p.id[a]));
    owned.contacts.push_back(b < 0 ? static_cast<double>(b) : static_cast<double>(p.id[static_cast<std::size_t>(b)]));
    owned.contacts.insert(owned.contacts.end(), list.history.begin() + static_cast<std::ptrdiff_t>(k * list.history_stride),
                          list.history.begin() + static_cast<std::ptrdiff_t>((k + 1) * list.history_stride));
  }
  events_ = from.events;
  distribute(std::move(owned), max_over_ranks(longest, comm_), setup, &from);
}

DistributedSimulation::~DistributedSimulation() = default;

// The first partition: cuts the grid, sends every particle, bond and touching contact to its owner
// and the ghost copies to the ranks next to it, then builds this rank's Simulation (the later
// partitions move only what changes owner: repartition.cpp).
void DistributedSimulation::distribute(Owned owned, double longest_bond, SimulationSetup& initial,
                                       const SimulationState* resumed) {
  const double start = MPI_Wtime();
  std::sort(owned.particles.begin(), owned.particles.end(), by_id);
  const std::size_t bond_record = 2 + owned.bond_stride;
  const FlatRecords bonds{owned.bonds, bond_record}, contacts{owned.contacts, 2 + owned.history_stride};
  const CellGrid grid = partition_grid(lowest(owned.particles), r_max_, longest_bond, skin_, comm_);
  std::vector<std::uint64_t> key;
  const Partition partition =
      Partition::balance(all_gather(cell_costs(owned.particles, bonds, contacts, grid, key), comm_), ranks_, grid.cell);

  // Where everything goes.
  const auto R = static_cast<std::size_t>(ranks_);
  Arrived in;
  {
    const Outgoing out = route(owned.particles, bonds, contacts, partition, key, R);
    owned = Owned{};
    in = exchange(out, comm_);
  }
  Particles local = local_particles(in);
  std::vector<std::pair<Index, std::uint64_t>> cells;
  cells.reserve(in.mine.size());
  for (const ParticleRecord& r : in.mine) cells.emplace_back(r.id, grid.key(Vec3(r.position[0], r.position[1], r.position[2])));
  halo_->reset(halo_links(cells, in.ghosts, partition, rank_, R));

  // The state values each bond record carries (the same on every rank: none for a new scene's).
  const std::size_t bond_stride = bond_record - 2;
  const std::size_t history_stride = contact_ ? contact_->history_size() : 0;
  LocalLinks links = local_links(in, bond_stride, history_stride, skin_, rank_);
  owned_ = in.mine.size();

  build_local(std::move(initial), resumed, local, links.bond_ends);
  if (resumed) import_local(*resumed, std::move(local), links.bond_ends, in.bonds, bond_stride, std::move(links.touching));
  position_at_partition_ = local_->particles().position;
  partition_id_ = local_->particles().id;
  partition_seconds_ += MPI_Wtime() - start;
  if (!resumed) finish_step();  // the first force pass's wall loads and breaks
}

// The scene's set-up as a serial run takes it (models, materials, walls, settings), with this
// rank's particles and bonds in place of the whole scene's. A resumed run imports them again
// (import_local), so they are copied, not moved.
void DistributedSimulation::build_local(SimulationSetup s, const SimulationState* resumed, Particles& local,
                                        std::vector<std::pair<Index, Index>>& bond_ends) {
  s.particles = resumed ? local : std::move(local);
  s.bonds = resumed ? bond_ends : std::move(bond_ends);
  s.skin = skin_;
  s.dt = resumed ? resumed->dt : s.dt;
  if (!(s.dt > 0)) {
    // "auto": every rank's models state their limits over its particles and bonds (a probe
    // without the halo); the smallest over the ranks is the serial run's.
    SimulationSetup probe = s;
    s.dt = min_over_ranks(Simulation(std::move(probe)).dt(), comm_);
  }
  s.exchange = halo_.get();
  local_ = std::make_unique<Simulation>(std::move(s));
}

// A resumed run's particles, bonds (with their state from `bond_records`) and touching contacts of
// this rank into its Simulation.
void DistributedSimulation::import_local(const SimulationState& resumed, Particles local,
                                         const std::vector<std::pair<Index, Index>>& bond_ends,
                                         const std::vector<double>& bond_records, std::size_t bond_stride,
                                         NeighbourState touching) {
  SimulationState s;
  s.step = resumed.step;
  s.time = resumed.time;
  s.dt = resumed.dt;
  s.particles = std::move(local);
  s.bonds.stride = bond_stride;
  s.bonds.resize(bond_ends.size());
  for (std::size_t b = 0; b < bond_ends.size(); ++b) {
    s.bonds.i[b] = std::min(bond_ends[b].first, bond_ends[b].second);
    s.bonds.j[b] = std::max(bond_ends[b].first, bond_ends[b].second);
    std::copy_n(bond_records.data() + b * (2 + bond_stride) + 2, bond_stride, s.bonds.state.data() + b * bond_stride);
  }
  // The loads are the run's (the same on every rank, as walls() promises); the work and the
  // impacts a rank counts from here on are its own, summed when gathered: rank 0 keeps the past.
  for (WallState w : resumed.walls) {
    if (rank_ != 0) {
      w.contact_work = 0;
      w.impacts = 0;
    }
    s.walls.push_back(w);
  }
  touching.rebuilds = resumed.neighbours.rebuilds;
  s.neighbours = std::move(touching);  // no build positions: the next force pass rebuilds the list
  local_->import_state(std::move(s));
}

void DistributedSimulation::step() {
  local_->step();
  finish_step();
}

void DistributedSimulation::run(std::int64_t steps) {
  for (std::int64_t s = 0; s < steps; ++s) step();
}

// After a step: the new break events, the wall contacts begun (by id, and their count over the
// ranks), the walls' loads summed over the ranks (a wall driven by its force then moves alike
// everywhere), and whether to re-partition. One gather of a few numbers per rank; a second only
// when some bond broke.
void DistributedSimulation::finish_step() {
  Simulation& sim = *local_;
  std::vector<BondBreakEvent> fresh = sim.take_new_break_events();
  const Particles& p = sim.particles();
  follow_by_id(p, partition_id_, position_at_partition_);
  begun_.clear();
  const bool bodies = p.body.size() == p.size();
  for (const WallContactStart& c : sim.wall_contacts_begun()) {
    const auto k = static_cast<std::size_t>(c.particle);
    if (p.flags[k] & kGhost) continue;  // the neighbour list pairs walls with owned particles only
    begun_.push_back({p.id[k], bodies ? p.body[k] : 0, c.wall, c.normal});
  }
  std::vector<Wall>& walls = sim.walls();
  const std::vector<double> mine = step_figures(fresh.size(), p, position_at_partition_, sim.dt(), begun_.size(), walls);
  double reduction_start = MPI_Wtime();
  if (timing_barriers_) {
    MPI_Barrier(comm_);
    const double after = MPI_Wtime();
    reduction_barrier_seconds_ += after - reduction_start;
    reduction_start = after;
  }
  const std::vector<double> all = all_gather(mine, comm_);
  reduction_seconds_ += MPI_Wtime() - reduction_start;
  const StepTotals totals = add_up_ranks(all, mine.size(), ranks_, walls);
  wall_contacts_begun_anywhere_ = static_cast<std::int64_t>(totals.begun);
  if (totals.events > 0) gather_break_events(fresh, comm_, events_);
  // Also when not finite: the partition then names the particle.
  if (!(totals.max_moved < 0.5 * skin_)) repartition();
}

std::size_t DistributedSimulation::ghosts() const { return halo_->ghosts(); }
double DistributedSimulation::halo_seconds() const { return halo_->seconds(); }

DistributedSimulation::PhaseSeconds DistributedSimulation::phase_seconds() const {
  const Halo::Times& h = halo_->times();
  return {h.pack, h.exchange, h.unpack, h.barrier + reduction_barrier_seconds_, reduction_seconds_, partition_seconds_,
          repartition_cpu_seconds_};
}

void DistributedSimulation::set_timing_barriers(bool on) {
  timing_barriers_ = on;
  halo_->set_barriers(on);
}

std::size_t DistributedSimulation::halo_neighbours() const { return halo_->links().size(); }

Energies DistributedSimulation::energies() const {
  const Particles& p = local_->particles();
  double kinetic = 0, gravity = 0;
  for (std::size_t k = 0; k < p.size(); ++k) {
    if (p.flags[k] & kGhost) continue;
    kinetic += 0.5 * p.mass[k] * p.velocity[k].squaredNorm() + 0.5 * p.inertia[k] * p.omega[k].squaredNorm();
    gravity -= p.mass[k] * gravity_.dot(p.position[k]);
  }
  const Energies local = local_->energies();  // bonds and contacts: this rank's own only
  Energies e;
  e.kinetic = sum_in_rank_order(kinetic, comm_);
  e.gravity = sum_in_rank_order(gravity, comm_);
  e.bond = sum_in_rank_order(local.bond, comm_);
  e.contact = sum_in_rank_order(local.contact, comm_);
  return e;
}

std::size_t DistributedSimulation::contact_count() const {
  return static_cast<std::size_t>(sum_in_rank_order(static_cast<double>(local_->contact_count()), comm_));
}

std::size_t DistributedSimulation::bond_count() const {
  return static_cast<std::size_t>(sum_in_rank_order(static_cast<double>(local_->bonds().size()), comm_));
}

void DistributedSimulation::check_finite() const {
  const Particles& p = local_->particles();
  double bad = 0;
  for (std::size_t k = 0; k < p.size() && bad == 0; ++k)
    if (!(p.flags[k] & kGhost) && !(p.position[k].allFinite() && p.velocity[k].allFinite())) bad = 1;
  if (max_over_ranks(bad, comm_) > 0)
    throw std::runtime_error(fmt::format("the run has blown up at step {}: a particle's position or velocity is not "
                                         "finite (reduce dt or check the contact and bond stiffness)",
                                         step_count()));
}

GatheredParticles DistributedSimulation::gather(int root) const {
  const Particles& p = local_->particles();
  std::vector<ParticleRecord> mine;
  for (std::size_t k = 0; k < p.size(); ++k)
    if (!(p.flags[k] & kGhost)) mine.push_back(record_of(p, k));
  // An all-gather keeps this short; the output of a large run would use MPI_Gatherv or parallel HDF5.
  std::vector<ParticleRecord> all = all_gather(mine, comm_);
  GatheredParticles g;
  if (rank_ != root) return g;
  std::sort(all.begin(), all.end(), by_id);
  for (const ParticleRecord& r : all) {
    g.id.push_back(r.id);
    g.position.emplace_back(r.position[0], r.position[1], r.position[2]);
    g.velocity.emplace_back(r.velocity[0], r.velocity[1], r.velocity[2]);
    g.omega.emplace_back(r.omega[0], r.omega[1], r.omega[2]);
    Quat q;
    std::copy_n(r.orientation, 4, q.coeffs().data());
    g.orientation.push_back(q);
  }
  return g;
}

std::vector<double> DistributedSimulation::sum_over_ranks(const std::vector<double>& mine) const {
  return sum_in_rank_order(mine, comm_);
}

std::vector<double> DistributedSimulation::gather_over_ranks(const std::vector<double>& mine) const {
  return all_gather(mine, comm_);
}

std::vector<double> DistributedSimulation::gather_to_root(const std::vector<double>& mine, int root) const {
  return gather_to(mine, root, comm_);
}

std::vector<Index> DistributedSimulation::gather_to_root(const std::vector<Index>& mine, int root) const {
  return gather_to(mine, root, comm_);
}

std::vector<Index> DistributedSimulation::scatter_from_root(const std::vector<Index>& all, std::size_t mine,
                                                            int root) const {
  const int count = byte_count(mine * sizeof(Index)) / static_cast<int>(sizeof(Index));
  std::vector<int> counts(static_cast<std::size_t>(ranks_)), at(static_cast<std::size_t>(ranks_));
  MPI_Gather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, root, comm_);
  int total = 0;
  for (int r = 0; r < ranks_; ++r) {
    at[static_cast<std::size_t>(r)] = total;
    total += counts[static_cast<std::size_t>(r)];
  }
  if (rank_ == root && static_cast<std::size_t>(total) != all.size())
    throw std::logic_error(fmt::format("scatter_from_root: {} values for {} asked", all.size(), total));
  std::vector<Index> out(mine);
  static_assert(sizeof(Index) == sizeof(std::int32_t));
  MPI_Scatterv(all.data(), counts.data(), at.data(), MPI_INT32_T, out.data(), count, MPI_INT32_T, root, comm_);
  return out;
}

bool DistributedSimulation::any_rank(bool mine) const { return max_over_ranks(mine ? 1.0 : 0.0, comm_) > 0; }

bool DistributedSimulation::all_slower_than(double speed) const {
  const Particles& p = local_->particles();
  const double limit2 = speed * speed;
  int mine = 1;
  for (std::size_t k = 0; k < p.size() && mine; ++k)
    if (!(p.flags[k] & kGhost) && p.velocity[k].squaredNorm() >= limit2) mine = 0;
  int all = 0;
  MPI_Allreduce(&mine, &all, 1, MPI_INT, MPI_LAND, comm_);
  return all != 0;
}

}  // namespace shard::mpi
