#pragma once
// Typed collectives over trivially copyable records (both ends run the same binary, so records
// travel as bytes). Every result is ordered by source rank, so what a rank does with it depends
// only on the data and the rank count: runs are bit-reproducible for a given rank count.
#include <mpi.h>

#include <cstddef>
#include <stdexcept>
#include <type_traits>
#include <vector>

namespace shard::mpi {

inline int rank_of(MPI_Comm comm) {
  int r = 0;
  MPI_Comm_rank(comm, &r);
  return r;
}

inline int size_of(MPI_Comm comm) {
  int s = 1;
  MPI_Comm_size(comm, &s);
  return s;
}

inline int byte_count(std::size_t bytes) {
  if (bytes > static_cast<std::size_t>(INT32_MAX))
    throw std::length_error("an MPI message above 2 GiB: run on more ranks");
  return static_cast<int>(bytes);
}

// out[r]: the records for rank r. Returns the records received, concatenated in source-rank order;
// with `from`, how many came from each rank.
template <class T>
std::vector<T> all_to_all(const std::vector<std::vector<T>>& out, MPI_Comm comm, std::vector<std::size_t>* from = nullptr) {
  static_assert(std::is_trivially_copyable_v<T>);
  const int n = size_of(comm);
  std::vector<int> send_count(static_cast<std::size_t>(n)), recv_count(static_cast<std::size_t>(n));
  std::vector<int> send_at(static_cast<std::size_t>(n)), recv_at(static_cast<std::size_t>(n));
  std::vector<T> send;
  for (int r = 0; r < n; ++r) {
    const auto& part = out[static_cast<std::size_t>(r)];
    send_at[static_cast<std::size_t>(r)] = byte_count(send.size() * sizeof(T));
    send_count[static_cast<std::size_t>(r)] = byte_count(part.size() * sizeof(T));
    send.insert(send.end(), part.begin(), part.end());
  }
  MPI_Alltoall(send_count.data(), 1, MPI_INT, recv_count.data(), 1, MPI_INT, comm);
  std::size_t total = 0;
  for (int r = 0; r < n; ++r) {
    recv_at[static_cast<std::size_t>(r)] = byte_count(total);
    total += static_cast<std::size_t>(recv_count[static_cast<std::size_t>(r)]);
  }
  std::vector<T> in(total / sizeof(T));
  if (from)
    for (int r = 0; r < n; ++r) from->push_back(static_cast<std::size_t>(recv_count[static_cast<std::size_t>(r)]) / sizeof(T));
  MPI_Alltoallv(send.data(), send_count.data(), send_at.data(), MPI_BYTE, in.data(), recv_count.data(),
                recv_at.data(), MPI_BYTE, comm);
  return in;
}

// Every rank's `mine`, concatenated in rank order, on every rank.
template <class T>
std::vector<T> all_gather(const std::vector<T>& mine, MPI_Comm comm) {
  static_assert(std::is_trivially_copyable_v<T>);
  const int n = size_of(comm);
  const int bytes = byte_count(mine.size() * sizeof(T));
  std::vector<int> count(static_cast<std::size_t>(n)), at(static_cast<std::size_t>(n));
  MPI_Allgather(&bytes, 1, MPI_INT, count.data(), 1, MPI_INT, comm);
  std::size_t total = 0;
  for (int r = 0; r < n; ++r) {
    at[static_cast<std::size_t>(r)] = byte_count(total);
    total += static_cast<std::size_t>(count[static_cast<std::size_t>(r)]);
  }
  std::vector<T> all(total / sizeof(T));
  MPI_Allgatherv(mine.data(), bytes, MPI_BYTE, all.data(), count.data(), at.data(), MPI_BYTE, comm);
  return all;
}

// Every rank's `mine`, concatenated in rank order, on `root` only (empty elsewhere): what a
// writer on one rank needs, without every rank holding the whole run.
template <class T>
std::vector<T> gather_to(const std::vector<T>& mine, int root, MPI_Comm comm) {
  static_assert(std::is_trivially_copyable_v<T>);
  const int n = size_of(comm);
  const int bytes = byte_count(mine.size() * sizeof(T));
  std::vector<int> count(static_cast<std::size_t>(n)), at(static_cast<std::size_t>(n));
  MPI_Gather(&bytes, 1, MPI_INT, count.data(), 1, MPI_INT, root, comm);
  std::size_t total = 0;
  if (rank_of(comm) == root)
    for (int r = 0; r < n; ++r) {
      at[static_cast<std::size_t>(r)] = byte_count(total);
      total += static_cast<std::size_t>(count[static_cast<std::size_t>(r)]);
    }
  std::vector<T> all(total / sizeof(T));
  MPI_Gatherv(mine.data(), bytes, MPI_BYTE, all.data(), count.data(), at.data(), MPI_BYTE, root, comm);
  return all;
}

// Element-wise sums over ranks of equally long vectors, added in rank order.
inline std::vector<double> sum_in_rank_order(const std::vector<double>& mine, MPI_Comm comm) {
  const std::vector<double> all = all_gather(mine, comm);
  std::vector<double> total(mine.size(), 0.0);
  for (std::size_t r = 0; r * mine.size() < all.size(); ++r)
    for (std::size_t k = 0; k < mine.size(); ++k) total[k] += all[r * mine.size() + k];
  return total;
}

// The sum over ranks of one value per rank, added in rank order (MPI_Allreduce may add in any
// order, and a different order rounds differently).
inline double sum_in_rank_order(double mine, MPI_Comm comm) {
  double total = 0;
  for (double v : all_gather(std::vector<double>{mine}, comm)) total += v;
  return total;
}

inline double max_over_ranks(double mine, MPI_Comm comm) {
  double out = 0;
  MPI_Allreduce(&mine, &out, 1, MPI_DOUBLE, MPI_MAX, comm);
  return out;
}

inline double min_over_ranks(double mine, MPI_Comm comm) {
  double out = 0;
  MPI_Allreduce(&mine, &out, 1, MPI_DOUBLE, MPI_MIN, comm);
  return out;
}

}  // namespace shard::mpi
