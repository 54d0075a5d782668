#pragma once
// The rows of a table that every rank writes at once (a frame, a checkpoint: the serial layout):
// each rank's own particles in ascending id from the exclusive prefix sum of the ranks' counts.
// A rank's bonds and contacts name their ends by those rows; a ghost end's row is its owner's,
// asked over the halo links (one integer per ghost).
#include <mpi.h>

#include <cstdint>
#include <utility>
#include <vector>

#include "halo.hpp"

namespace shard::mpi {

// Where one rank's rows of a table go.
struct RowRange {
  std::size_t first = 0, total = 0;
};

// For each of `counts` (this rank's rows of several tables): its first row and the whole table's.
std::vector<RowRange> row_ranges(const std::vector<unsigned long long>& counts, MPI_Comm comm);

class GlobalRows {
 public:
  // `own_ids`: this rank's own particles in ascending id, at rows first_row, first_row + 1, ...
  GlobalRows(std::vector<Index> own_ids, std::size_t first_row, const std::vector<HaloLink>& links, MPI_Comm comm);
  // The row of a particle held here (own or ghost); throws std::logic_error for any other.
  Index operator()(Index id) const;

 private:
  std::int64_t own_row(Index id) const;
  std::vector<Index> own_;
  std::size_t first_ = 0;
  std::vector<std::pair<Index, std::int64_t>> ghost_;  // (id, row), ascending id
};

}  // namespace shard::mpi
