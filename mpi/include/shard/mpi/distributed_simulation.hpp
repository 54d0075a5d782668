#pragma once
// A run decomposed in space over MPI ranks (docs/explanation/scaling.md). Each rank steps a Simulation of
// the particles it owns plus ghost copies of its neighbours' particles near the border; pairs and
// bonds are computed once, by the rank owning the end with the smaller stable id, and the reaction
// on a ghost end goes back to its owner (halo.hpp). The partition is a cost-balanced cut of the
// Morton-ordered neighbour-cell grid, re-balanced, with migration, whenever some particle may have
// moved half the Verlet skin since the last one (when the serial run rebuilds its list). Global quantities (time step, wall loads, break
// log, energies) are reduced in rank order. Plugins are unchanged: they see a particle view.
//
// Every call is collective over the communicator unless it says otherwise.
#include <mpi.h>

#include <cstdint>
#include <memory>
#include <utility>
#include <vector>

#include "shard/checkpoint.hpp"
#include "shard/simulation.hpp"

namespace shard::mpi {

class Halo;

// The run's particles gathered on one rank, in ascending stable id.
struct GatheredParticles {
  std::vector<Index> id;
  std::vector<Vec3> position, velocity, omega;
  std::vector<Quat> orientation;
};

// A frame of the run file (docs/reference/output-format.md) on one rank: the particles in ascending stable id
// with the fields a frame stores filled (position, velocity, omega, radius, mass, material, body,
// id; the others empty), and the surviving bonds as index pairs into them, in ascending
// (smaller id, larger id), without model state.
struct GatheredFrame {
  Particles particles;
  Bonds bonds;
};

// This rank's rows of a frame written by every rank at once (RunWriter::write_frame_part): its own
// particles in ascending id (the fields a frame stores) at the exclusive prefix sum of the ranks'
// counts, and its own bonds as row pairs into the whole frame at theirs.
struct FrameShare {
  Particles particles;
  std::size_t first_row = 0, total_rows = 0;
  std::vector<Index> bond_rows;  // (row of the smaller id, row of the larger) per bond
  std::size_t first_bond = 0, total_bonds = 0;
};

// This rank's share of a checkpoint that every rank writes at once (write_checkpoint_share): its own
// particles in ascending id, its own bonds and touching contacts with their ends as rows of the
// whole file, at the rows given; the rest (step, walls, break log, totals) the whole run's, the
// same on every rank.
struct StateShare {
  SimulationState state;
  CheckpointRows particles, bonds, contacts;
};

// The fragment labels of a frame (mpi/src/fragment_labels.cpp): what the serial labeller and
// analysis::canonicalise_labels give the whole run, computed where the particles are.
struct FragmentLabels {
  std::vector<Index> labels;        // this rank's own particles in ascending id (FrameShare's rows)
  std::vector<std::size_t> sizes;   // particles per fragment, largest first, on rank 0 (empty elsewhere)
  int rounds = 0;                   // border exchanges until no fragment's name changed
};

class DistributedSimulation {
 public:
  // `setup` is the whole scene, the same on every rank (each keeps its part). Throws
  // std::invalid_argument, on every rank alike, when the rank count cannot hold the partition.
  DistributedSimulation(MPI_Comm comm, SimulationSetup setup);
  // `share` holds this rank's share of the scene: any split of its particles, each rank's bonds
  // between its own particles (rank 0 holding the whole scene that it alone generated, the others
  // none, is one). The models, walls and settings are the scene's on every rank. The first
  // partition sends every particle and bond to its owner; no rank needs the whole scene.
  struct ScatteredScene {};
  DistributedSimulation(MPI_Comm comm, SimulationSetup share, ScatteredScene);
  // Continues a run from its whole state `from` (a checkpoint, written on any rank count or by the
  // serial build: particles, bonds and contacts are matched by stable id), the same on every rank.
  // `setup` is the scene's (models, walls, damping); its particles and bonds are not used.
  DistributedSimulation(MPI_Comm comm, SimulationSetup setup, const SimulationState& from);
  ~DistributedSimulation();
  DistributedSimulation(const DistributedSimulation&) = delete;
  DistributedSimulation& operator=(const DistributedSimulation&) = delete;

  void step();
  void run(std::int64_t steps);
  // Cuts the grid anew from the current positions and costs; what step() does by itself when
  // some particle may have moved half the skin since the last cut. Each rank keeps the particles
  // it still owns in place and sends only those whose new owner differs, with the bonds and
  // touching contacts they own (mpi/src/repartition.cpp).
  void repartition();

  // Local, the same on every rank.
  int rank() const { return rank_; }
  int ranks() const { return ranks_; }
  double time() const { return local_->time(); }
  double dt() const { return local_->dt(); }
  std::int64_t step_count() const { return local_->step_count(); }
  const std::vector<Wall>& walls() const { return local_->walls(); }  // loads summed over ranks
  // Every rank's break events of the run, sorted by (step, smaller id, larger id); id_i < id_j.
  const std::vector<BondBreakEvent>& break_events() const { return events_; }
  // How many wall contacts began in the last step over all ranks (counted in the step's own
  // reduction: knowing it costs no message).
  std::int64_t wall_contacts_begun_anywhere() const { return wall_contacts_begun_anywhere_; }
  std::int64_t bonds_broken() const { return static_cast<std::int64_t>(events_.size()); }
  std::int64_t repartitions() const { return repartitions_; }
  // What re-partitions sent from this rank to the others (local): the particles whose owner
  // changed, and the bonds and touching contacts that travelled with them.
  struct Migration {
    std::size_t particles = 0, bonds = 0, contacts = 0;
  };
  const Migration& last_migration() const { return last_migration_; }  // the latest re-partition's
  const Migration& migration_total() const { return migration_total_; }  // the run's

  // Local, this rank's share.
  const Simulation& local() const { return *local_; }
  // For a run loop's observers, which read it (stepping it alone would break the decomposition).
  Simulation& local() { return *local_; }
  // Whether the particle at `k` of local().particles() is this rank's own (not a ghost copy).
  bool owns(std::size_t k) const { return !(local_->particles().flags[k] & kGhost); }
  // The wall contacts begun in the last step on this rank's own particles, named by stable id and
  // body: a re-partition at the end of the step renumbers the local particles, which would leave
  // Simulation::wall_contacts_begun's indices pointing at others.
  struct WallContactBegun {
    Index id = 0;
    std::int32_t body = 0;
    std::int32_t wall = 0;
    Vec3 normal = Vec3::Zero();  // unit, from the wall towards the particle
  };
  const std::vector<WallContactBegun>& wall_contacts_begun() const { return begun_; }
  std::size_t owned() const { return owned_; }
  std::size_t ghosts() const;
  double halo_seconds() const;      // wall time in the per-step ghost and reaction exchanges
  double partition_seconds() const { return partition_seconds_; }  // in re-partitions and migration
  // Wall time by phase so far (bench_mpi's cost model, docs/explanation/scaling.md): the halo's packing
  // (and locating by id), messages (post to Waitall) and unpacking, the per-step reduction
  // (all-gather), re-partitions; `barrier` is the time in a barrier put before each exchange and
  // the reduction when `set_timing_barriers(true)`, which separates waiting for the slowest rank
  // from the transfer itself (a measurement aid: it adds synchronisation).
  // `repartition_cpu`: the CPU time of this rank's thread in the re-partitions after the first
  // partition (on a shared machine their wall time counts the waiting for a core).
  struct PhaseSeconds {
    double pack = 0, exchange = 0, unpack = 0, barrier = 0, reduction = 0, partition = 0, repartition_cpu = 0;
  };
  PhaseSeconds phase_seconds() const;
  void set_timing_barriers(bool on);
  std::size_t halo_neighbours() const;  // ranks this one exchanges with each step

  // Collective.
  Energies energies() const;
  std::size_t contact_count() const;
  std::size_t bond_count() const;
  // Throws std::runtime_error on every rank when some rank holds a non-finite position or velocity.
  void check_finite() const;
  // All particles on `root` (empty elsewhere).
  GatheredParticles gather(int root = 0) const;
  // The whole run's state on `root` (empty elsewhere), as one serial Simulation would export it:
  // particles in ascending stable id, bonds (with model state) as index pairs into them, the
  // break log, the walls (impacts and dissipated work summed over the ranks), and with
  // `contacts` the touching pairs' history (no list build positions: the importer rebuilds).
  // What a frame and a checkpoint hold; a checkpoint of it restarts on any rank count.
  SimulationState gather_state(int root = 0, bool contacts = true) const;
  // The same state as every rank's share of one file, nothing gathered: prefix sums of the ranks'
  // counts and the rows of the ghosts' owners through the halo links.
  StateShare state_share(bool contacts = true) const;
  // A frame's content on `root` (empty elsewhere), by MPI_Gatherv: per particle 11 doubles and 3
  // integers, per bond two ids, against gather_state's 22 doubles, 5 integers and 2 + stride
  // doubles (mpi/src/frame_gather.cpp).
  GatheredFrame gather_frame(int root = 0) const;
  // This rank's share of a frame, nothing gathered: two prefix sums, and the rows of the ghosts'
  // owners through the halo links (one integer per ghost).
  FrameShare frame_share() const;
  // The fragments of the surviving bonds by a distributed union-find: each rank's own components,
  // merged across borders over the halo links, numbered canonically on rank 0 from one record per
  // fragment and rank (docs/explanation/scaling.md).
  FragmentLabels label_fragments() const;
  // Element-wise sums over the ranks, added in rank order (the same on every rank).
  std::vector<double> sum_over_ranks(const std::vector<double>& mine) const;
  // Every rank's `mine` (of any length), concatenated in rank order, on every rank.
  std::vector<double> gather_over_ranks(const std::vector<double>& mine) const;
  // Every rank's `mine`, concatenated in rank order, on `root` only (empty elsewhere).
  std::vector<double> gather_to_root(const std::vector<double>& mine, int root = 0) const;
  std::vector<Index> gather_to_root(const std::vector<Index>& mine, int root = 0) const;
  // The inverse: `all` on `root` cut in rank order, each rank receiving its `mine` values.
  std::vector<Index> scatter_from_root(const std::vector<Index>& all, std::size_t mine, int root = 0) const;
  // True when any rank passes true (one MPI_Allreduce).
  bool any_rank(bool mine) const;
  // Whether every particle of the run is slower than `speed` (m/s): each rank looks at its own
  // (stopping at the first too fast), one MPI_Allreduce (logical and) combines the answers.
  bool all_slower_than(double speed) const;

 private:
  struct Owned;
  double take_rows(const SimulationSetup& setup, std::size_t begin, std::size_t end, Owned& owned) const;
  void find_largest_radius(const Particles& p);
  // `initial`: the scene's set-up, taken over (moved from) to build this rank's Simulation.
  void distribute(Owned owned, double longest_bond, SimulationSetup& initial, const SimulationState* resumed = nullptr);
  void build_local(SimulationSetup s, const SimulationState* resumed, Particles& local,
                   std::vector<std::pair<Index, Index>>& bond_ends);
  void import_local(const SimulationState& resumed, Particles local, const std::vector<std::pair<Index, Index>>& bond_ends,
                    const std::vector<double>& bond_records, std::size_t bond_stride, NeighbourState touching);
  void start(const SimulationSetup& setup);
  void finish_step();
  void fill_whole_figures(SimulationState& s) const;

  MPI_Comm comm_;
  int rank_ = 0, ranks_ = 1;
  const ContactModel* contact_;
  const BondModel* bond_;
  double skin_ = 0;  // the Verlet skin, m (the serial run's)
  double r_max_ = 0;
  std::unique_ptr<Halo> halo_;
  std::unique_ptr<Simulation> local_;
  std::size_t owned_ = 0;
  Vec3 gravity_ = Vec3::Zero();
  // Positions at the last partition and the ids they belong to, in the local order.
  std::vector<Vec3> position_at_partition_;
  std::vector<Index> partition_id_;
  std::vector<BondBreakEvent> events_;
  std::vector<WallContactBegun> begun_;
  std::int64_t wall_contacts_begun_anywhere_ = 0;
  std::int64_t repartitions_ = 0;
  Migration last_migration_, migration_total_;
  double partition_seconds_ = 0, repartition_cpu_seconds_ = 0;
  double reduction_seconds_ = 0, reduction_barrier_seconds_ = 0;
  bool timing_barriers_ = false;
};

}  // namespace shard::mpi
