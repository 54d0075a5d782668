#include "halo.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <stdexcept>
#include <unordered_map>

namespace shard::mpi {
namespace {

constexpr std::size_t kStateDoubles = 13;  // position 3, velocity 3, orientation 4, spin 3
constexpr std::size_t kLoadDoubles = 6;    // force 3, torque 3
constexpr int kTagState = 71, kTagLoad = 72;

bool still_at(const Particles& p, const std::vector<Index>& ids, const std::vector<std::size_t>& index) {
  if (index.size() != ids.size()) return false;
  for (std::size_t k = 0; k < ids.size(); ++k)
    if (index[k] >= p.size() || p.id[index[k]] != ids[k]) return false;
  return true;
}

}  // namespace

void Halo::reset(std::vector<HaloLink> links) {
  links_ = std::move(links);
  send_index_.assign(links_.size(), {});
  recv_index_.assign(links_.size(), {});
  send_buffer_.resize(links_.size());
  recv_buffer_.resize(links_.size());
}

std::size_t Halo::ghosts() const {
  std::size_t g = 0;
  for (const HaloLink& l : links_) g += l.recv.size();
  return g;
}

void Halo::locate(const Particles& p) {
  bool valid = true;
  for (std::size_t l = 0; l < links_.size() && valid; ++l)
    valid = still_at(p, links_[l].send, send_index_[l]) && still_at(p, links_[l].recv, recv_index_[l]);
  if (valid) return;
  std::unordered_map<Index, std::size_t> where;
  where.reserve(p.size());
  for (std::size_t k = 0; k < p.size(); ++k) where.emplace(p.id[k], k);
  const auto find = [&](Index id, bool ghost) {
    const auto it = where.find(id);
    if (it == where.end() || ((p.flags[it->second] & kGhost) != 0) != ghost)
      throw std::logic_error(fmt::format("halo: particle id {} is not held here as {}", id, ghost ? "a ghost" : "owned"));
    return it->second;
  };
  for (std::size_t l = 0; l < links_.size(); ++l) {
    send_index_[l].resize(links_[l].send.size());
    recv_index_[l].resize(links_[l].recv.size());
    for (std::size_t k = 0; k < links_[l].send.size(); ++k) send_index_[l][k] = find(links_[l].send[k], false);
    for (std::size_t k = 0; k < links_[l].recv.size(); ++k) recv_index_[l][k] = find(links_[l].recv[k], true);
  }
}

// forward: owners -> ghosts (send lists out); otherwise ghosts -> owners (recv lists out).
void Halo::exchange(std::size_t per_recv, bool forward) {
  double t = MPI_Wtime();
  if (barriers_) {
    MPI_Barrier(comm_);
    const double after = MPI_Wtime();
    times_.barrier += after - t;
    t = after;
  }
  requests_.clear();
  const int tag = forward ? kTagState : kTagLoad;
  for (std::size_t l = 0; l < links_.size(); ++l) {
    const std::size_t count = (forward ? links_[l].recv.size() : links_[l].send.size()) * per_recv;
    recv_buffer_[l].resize(count);
    requests_.emplace_back();
    MPI_Irecv(recv_buffer_[l].data(), static_cast<int>(count), MPI_DOUBLE, links_[l].rank, tag, comm_, &requests_.back());
  }
  for (std::size_t l = 0; l < links_.size(); ++l) {
    requests_.emplace_back();
    MPI_Isend(send_buffer_[l].data(), static_cast<int>(send_buffer_[l].size()), MPI_DOUBLE, links_[l].rank, tag, comm_,
              &requests_.back());
  }
  MPI_Waitall(static_cast<int>(requests_.size()), requests_.data(), MPI_STATUSES_IGNORE);
  times_.exchange += MPI_Wtime() - t;
}

void Halo::refresh_ghosts(Particles& p) {
  const double start = MPI_Wtime();
  locate(p);
  for (std::size_t l = 0; l < links_.size(); ++l) {
    std::vector<double>& b = send_buffer_[l];
    b.resize(send_index_[l].size() * kStateDoubles);
    double* out = b.data();
    for (std::size_t k : send_index_[l]) {
      out = std::copy_n(p.position[k].data(), 3, out);
      out = std::copy_n(p.velocity[k].data(), 3, out);
      out = std::copy_n(p.orientation[k].coeffs().data(), 4, out);
      out = std::copy_n(p.omega[k].data(), 3, out);
    }
  }
  const double packed = MPI_Wtime();
  times_.pack += packed - start;
  exchange(kStateDoubles, true);
  const double received = MPI_Wtime();
  for (std::size_t l = 0; l < links_.size(); ++l) {
    const double* in = recv_buffer_[l].data();
    for (std::size_t k : recv_index_[l]) {
      std::copy_n(in, 3, p.position[k].data());
      std::copy_n(in + 3, 3, p.velocity[k].data());
      std::copy_n(in + 6, 4, p.orientation[k].coeffs().data());
      std::copy_n(in + 10, 3, p.omega[k].data());
      in += kStateDoubles;
    }
  }
  const double end = MPI_Wtime();
  times_.unpack += end - received;
  seconds_ += end - start;
}

void Halo::return_reactions(Particles& p) {
  const double start = MPI_Wtime();
  locate(p);
  for (std::size_t l = 0; l < links_.size(); ++l) {
    std::vector<double>& b = send_buffer_[l];
    b.resize(recv_index_[l].size() * kLoadDoubles);
    double* out = b.data();
    for (std::size_t k : recv_index_[l]) {
      out = std::copy_n(p.force[k].data(), 3, out);
      out = std::copy_n(p.torque[k].data(), 3, out);
      p.force[k].setZero();
      p.torque[k].setZero();
    }
  }
  const double packed = MPI_Wtime();
  times_.pack += packed - start;
  exchange(kLoadDoubles, false);
  const double received = MPI_Wtime();
  // Links are in ascending rank: each owned particle's reactions are added in rank order.
  for (std::size_t l = 0; l < links_.size(); ++l) {
    const double* in = recv_buffer_[l].data();
    for (std::size_t k : send_index_[l]) {
      p.force[k] += Vec3(in[0], in[1], in[2]);
      p.torque[k] += Vec3(in[3], in[4], in[5]);
      in += kLoadDoubles;
    }
  }
  const double end = MPI_Wtime();
  times_.unpack += end - received;
  seconds_ += end - start;
}

}  // namespace shard::mpi
