#pragma once
// What a decomposed run's partition would be on P ranks, computed in one process with the
// decomposition's own Partition (mpi/src/partition.hpp: every rank computes the same cut
// from the same cell costs): particles owned and ghosts held per rank and the ranks each one
// exchanges with. The cost model (docs/explanation/scaling.md) takes its ghost and neighbour counts at
// 16-256 ranks from here, without running that many ranks.
#include <cstdio>
#include <vector>

#include "shard/simulation.hpp"

namespace shard::bench {

// One summary line per rank count to `out`. Costs as the decomposition's first partition counts
// them: 1 per particle + 1 per bond (contacts are not counted: none is carried at the start).
void print_partitions(const char* label, const SimulationSetup& setup, const std::vector<int>& rank_counts, std::FILE* out);

}  // namespace shard::bench
