#include "partition_report.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <set>
#include <utility>

#include "../../mpi/src/partition.hpp"

namespace shard::bench {

void print_partitions(const char* label, const SimulationSetup& setup, const std::vector<int>& rank_counts, std::FILE* out) {
  const Particles& p = setup.particles;
  double r_max = 0, longest = 0;
  Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity());
  for (std::size_t k = 0; k < p.size(); ++k) {
    r_max = std::max(r_max, p.radius[k]);
    lo = lo.cwiseMin(p.position[k]);
  }
  std::vector<double> cost(p.size(), 1.0);
  for (const auto& [a, b] : setup.bonds) {
    const auto i = static_cast<std::size_t>(a), j = static_cast<std::size_t>(b);
    longest = std::max(longest, (p.position[i] - p.position[j]).norm());
    cost[p.id[i] < p.id[j] ? i : j] += 1;  // owned by the end with the smaller stable id
  }
  // The decomposition's grid (distributed_simulation.cpp, `distribute`).
  const double skin = setup.skin > 0 ? setup.skin : 0.2 * std::max(r_max, 1e-12);
  mpi::CellGrid grid;
  grid.cell = std::max(2 * r_max, longest) + skin;
  grid.origin = lo - Vec3::Constant(grid.cell);
  std::map<std::uint64_t, std::pair<double, std::size_t>> cells;  // key -> cost, particles
  for (std::size_t k = 0; k < p.size(); ++k) {
    auto& c = cells[grid.key(p.position[k])];
    c.first += cost[k];
    c.second += 1;
  }
  std::vector<mpi::CellCost> listed;
  for (const auto& [key, c] : cells) listed.push_back({key, c.first});
  std::fprintf(out, "partition_setup %s particles=%zu bonds=%zu cell_m=%.4g cells=%zu particles_per_cell=%.3f\n", label, p.size(),
               setup.bonds.size(), grid.cell, cells.size(), static_cast<double>(p.size()) / static_cast<double>(cells.size()));
  for (const int ranks : rank_counts) {
    const mpi::Partition part = mpi::Partition::balance(listed, ranks, grid.cell);
    const auto R = static_cast<std::size_t>(ranks);
    std::vector<double> owned(R), ghosts(R), rank_cost(R);
    std::vector<std::set<int>> linked(R);
    std::vector<int> around;
    for (const auto& [key, c] : cells) {
      const int o = part.owner_of(key);
      owned[static_cast<std::size_t>(o)] += static_cast<double>(c.second);
      rank_cost[static_cast<std::size_t>(o)] += c.first;
      part.neighbour_ranks(key, o, around);
      for (const int d : around) {
        ghosts[static_cast<std::size_t>(d)] += static_cast<double>(c.second);
        linked[static_cast<std::size_t>(d)].insert(o);
        linked[static_cast<std::size_t>(o)].insert(d);
      }
    }
    double ghost_sum = 0, ghost_max = 0, link_sum = 0, link_max = 0, cost_max = 0, cost_sum = 0, owned_max = 0;
    std::size_t busiest = 0;  // the rank of the largest cost: its ghosts and links set the pace
    for (std::size_t r = 0; r < R; ++r) {
      ghost_sum += ghosts[r];
      ghost_max = std::max(ghost_max, ghosts[r]);
      link_sum += static_cast<double>(linked[r].size());
      link_max = std::max(link_max, static_cast<double>(linked[r].size()));
      cost_sum += rank_cost[r];
      owned_max = std::max(owned_max, owned[r]);
      if (rank_cost[r] > cost_max) {
        cost_max = rank_cost[r];
        busiest = r;
      }
    }
    const double n = static_cast<double>(ranks);
    std::fprintf(out,
                 "partition %s ranks=%d owned_mean=%.1f owned_max=%.0f cost_imbalance=%.4f ghosts_mean=%.1f ghosts_max=%.0f "
                 "ghosts_busiest=%.0f ghost_ratio_mean=%.4f neighbours_mean=%.2f neighbours_max=%.0f\n",
                 label, ranks, static_cast<double>(p.size()) / n, owned_max, cost_max / (cost_sum / n), ghost_sum / n, ghost_max,
                 ghosts[busiest], ghost_sum / static_cast<double>(p.size()), link_sum / n, link_max);
  }
}

}  // namespace shard::bench
