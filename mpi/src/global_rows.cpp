#include "global_rows.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <limits>
#include <stdexcept>

namespace shard::mpi {
namespace {

constexpr int kRowsTag = 7301;  // the ghosts' rows (the halo's own messages use others)

}  // namespace

std::vector<RowRange> row_ranges(const std::vector<unsigned long long>& counts, MPI_Comm comm) {
  const int n = static_cast<int>(counts.size());
  std::vector<unsigned long long> before(counts.size(), 0), total(counts.size(), 0);
  MPI_Exscan(counts.data(), before.data(), n, MPI_UNSIGNED_LONG_LONG, MPI_SUM, comm);
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  if (rank == 0) std::fill(before.begin(), before.end(), 0ull);  // MPI_Exscan leaves rank 0's undefined
  MPI_Allreduce(counts.data(), total.data(), n, MPI_UNSIGNED_LONG_LONG, MPI_SUM, comm);
  std::vector<RowRange> out(counts.size());
  for (std::size_t k = 0; k < counts.size(); ++k) out[k] = {before[k], total[k]};
  return out;
}

GlobalRows::GlobalRows(std::vector<Index> own_ids, std::size_t first_row, const std::vector<HaloLink>& links,
                       MPI_Comm comm)
    : own_(std::move(own_ids)), first_(first_row) {
  // Each end of a link lists its ids in the same ascending order: the owner answers in `send`
  // order what the ghost's holder reads in `recv` order.
  std::vector<std::vector<std::int64_t>> out(links.size()), in(links.size());
  std::vector<MPI_Request> requests;
  requests.reserve(2 * links.size());
  for (std::size_t l = 0; l < links.size(); ++l) {
    for (Index id : links[l].send) out[l].push_back(own_row(id));
    in[l].resize(links[l].recv.size());
    requests.emplace_back();
    MPI_Irecv(in[l].data(), static_cast<int>(in[l].size()), MPI_INT64_T, links[l].rank, kRowsTag, comm,
              &requests.back());
    requests.emplace_back();
    MPI_Isend(out[l].data(), static_cast<int>(out[l].size()), MPI_INT64_T, links[l].rank, kRowsTag, comm,
              &requests.back());
  }
  MPI_Waitall(static_cast<int>(requests.size()), requests.data(), MPI_STATUSES_IGNORE);
  for (std::size_t l = 0; l < links.size(); ++l)
    for (std::size_t k = 0; k < in[l].size(); ++k) ghost_.emplace_back(links[l].recv[k], in[l][k]);
  std::sort(ghost_.begin(), ghost_.end());
}

std::int64_t GlobalRows::own_row(Index id) const {
  const auto it = std::lower_bound(own_.begin(), own_.end(), id);
  if (it == own_.end() || *it != id) return -1;
  return static_cast<std::int64_t>(first_) + (it - own_.begin());
}

Index GlobalRows::operator()(Index id) const {
  std::int64_t row = own_row(id);
  if (row < 0) {
    const auto it = std::lower_bound(ghost_.begin(), ghost_.end(), std::pair<Index, std::int64_t>{id, -1});
    if (it != ghost_.end() && it->first == id) row = it->second;
  }
  if (row < 0 || row > std::numeric_limits<Index>::max())
    throw std::logic_error(fmt::format("no row of the whole run for particle id {}", id));
  return static_cast<Index>(row);
}

}  // namespace shard::mpi
