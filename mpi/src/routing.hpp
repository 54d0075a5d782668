#pragma once
// What a partition sends where, shared by the first partition (distributed_simulation.cpp), which
// places every particle, and the later ones (repartition.cpp), which move only what changes
// owner: the grid, the ranks around a cell, the records on their way, their exchange, the halo.
#include <mpi.h>

#include <cstdint>
#include <unordered_map>
#include <utility>
#include <vector>

#include "halo.hpp"
#include "partition.hpp"
#include "records.hpp"

namespace shard::mpi {

// The grid: one cell reaches every particle an owned one can touch before the next partition
// (2 r_max + skin), and the far end of every bond. Collective: `lo` is the lower corner of this
// rank's owned particles (+infinity without any); the origin lies below every rank's.
CellGrid partition_grid(const Vec3& lo, double r_max, double longest_bond, double skin, MPI_Comm comm);

// The ranks owning the cells around a cell, looked up once per cell (27 searches each). Keyed by
// cell only: `self` must be the owner of the cell asked about.
class RanksAround {
 public:
  explicit RanksAround(const Partition& partition) : partition_(partition) {}
  const std::vector<int>& of(std::uint64_t cell, int self) {
    auto [it, fresh] = around_.try_emplace(cell);
    if (fresh) partition_.neighbour_ranks(cell, self, it->second);
    return it->second;
  }

 private:
  const Partition& partition_;
  std::unordered_map<std::uint64_t, std::vector<int>> around_;
};

// What this rank sends to each rank: particles it will own, ghost copies it will keep, and the
// bonds and touching contacts kept by the owner of their first particle (flat records: smaller id,
// larger id or -1 - wall, then the model state or history).
struct Outgoing {
  explicit Outgoing(std::size_t ranks) : to_owner(ranks), to_ghost(ranks), bonds_to(ranks), contacts_to(ranks) {}
  std::vector<std::vector<ParticleRecord>> to_owner, to_ghost;
  std::vector<std::vector<double>> bonds_to, contacts_to;
};

// What this rank received: particles it now owns and its ghosts (each ascending in id), and the
// bonds and contacts it now keeps.
struct Arrived {
  std::vector<ParticleRecord> mine, ghosts;
  std::vector<double> bonds, contacts;
  std::vector<std::size_t> bonds_from;  // doubles of `bonds` from each rank, in rank order
};

Arrived exchange(const Outgoing& out, MPI_Comm comm);

// The position of the record of particle `id` in `sorted` (ascending id); -1 when not there.
Index find_record(const std::vector<ParticleRecord>& sorted, Index id);

// The halo of a partition: which owned particles (id, cell) each neighbour keeps a ghost of
// (ascending id), and which ghosts come from whom.
std::vector<HaloLink> halo_links(const std::vector<std::pair<Index, std::uint64_t>>& owned,
                                 const std::vector<ParticleRecord>& ghosts, const Partition& partition, int rank,
                                 std::size_t ranks);

}  // namespace shard::mpi
