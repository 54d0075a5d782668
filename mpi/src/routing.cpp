#include "routing.hpp"

#include <algorithm>
#include <limits>

#include "comm.hpp"

namespace shard::mpi {

CellGrid partition_grid(const Vec3& lo, double r_max, double longest_bond, double skin, MPI_Comm comm) {
  const double mine[3] = {lo[0], lo[1], lo[2]};
  double global_lo[3];
  MPI_Allreduce(mine, global_lo, 3, MPI_DOUBLE, MPI_MIN, comm);
  CellGrid grid;
  grid.cell = std::max(2 * r_max, max_over_ranks(longest_bond, comm)) + skin;
  grid.origin = Vec3(global_lo[0], global_lo[1], global_lo[2]) - Vec3::Constant(grid.cell);
  return grid;
}

Arrived exchange(const Outgoing& out, MPI_Comm comm) {
  Arrived in;
  in.mine = all_to_all(out.to_owner, comm);
  in.ghosts = all_to_all(out.to_ghost, comm);
  in.bonds = all_to_all(out.bonds_to, comm, &in.bonds_from);
  in.contacts = all_to_all(out.contacts_to, comm);
  std::sort(in.mine.begin(), in.mine.end(), by_id);
  std::sort(in.ghosts.begin(), in.ghosts.end(), by_id);
  return in;
}

Index find_record(const std::vector<ParticleRecord>& sorted, Index id) {
  const auto it =
      std::lower_bound(sorted.begin(), sorted.end(), id, [](const ParticleRecord& r, Index x) { return r.id < x; });
  return it != sorted.end() && it->id == id ? static_cast<Index>(it - sorted.begin()) : Index{-1};
}

std::vector<HaloLink> halo_links(const std::vector<std::pair<Index, std::uint64_t>>& owned,
                                 const std::vector<ParticleRecord>& ghosts, const Partition& partition, int rank,
                                 std::size_t ranks) {
  std::vector<HaloLink> links(ranks);
  for (std::size_t r = 0; r < ranks; ++r) links[r].rank = static_cast<int>(r);
  RanksAround around(partition);
  for (const auto& [id, cell] : owned)
    for (int d : around.of(cell, rank)) links[static_cast<std::size_t>(d)].send.push_back(id);
  // Both ends list a link's particles in ascending id: the ghosts arrive sorted, the owned ones
  // are in the rank's local order.
  for (HaloLink& l : links) std::sort(l.send.begin(), l.send.end());
  for (const ParticleRecord& r : ghosts) links[static_cast<std::size_t>(r.owner)].recv.push_back(r.id);
  std::erase_if(links, [](const HaloLink& l) { return l.send.empty() && l.recv.empty(); });
  return links;
}

}  // namespace shard::mpi
