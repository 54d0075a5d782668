#pragma once
// The per-step halo exchange of a sub-domain (shard::DomainExchange over MPI): owners send their
// ghosts' copies the new position, velocity, orientation and spin after the drift; after the pair
// and bond pass each ghost's force and torque go back to the owner, which adds them in rank order.
// Between rebuilds only this is exchanged (docs/explanation/scaling.md).
#include <mpi.h>

#include <vector>

#include "shard/domain_exchange.hpp"

namespace shard::mpi {

// What this rank exchanges with one other rank every step, by stable id in a fixed order that
// both ends agree on (ascending id).
struct HaloLink {
  int rank = 0;
  std::vector<Index> send;  // owned here, ghosts there
  std::vector<Index> recv;  // ghosts here, owned there
};

class Halo final : public DomainExchange {
 public:
  explicit Halo(MPI_Comm comm) : comm_(comm) {}
  // New links at a re-partition (ascending rank).
  void reset(std::vector<HaloLink> links);
  void refresh_ghosts(Particles& particles) override;
  void return_reactions(Particles& particles) override;

  double seconds() const { return seconds_; }  // wall time spent in both exchanges so far
  // The same split by phase (bench_mpi's cost model, docs/explanation/scaling.md): copying into the send
  // buffers, the messages (post to Waitall), copying out; with `set_barriers(true)` a barrier
  // before each exchange takes the waiting for the slowest rank out of `exchange` into `barrier`.
  struct Times {
    double pack = 0, exchange = 0, unpack = 0, barrier = 0;
  };
  const Times& times() const { return times_; }
  void set_barriers(bool on) { barriers_ = on; }
  std::size_t ghosts() const;
  const std::vector<HaloLink>& links() const { return links_; }

 private:
  // Local indices of the links' ids; looked up again only when the kernel renumbered its
  // particles (the Morton renumbering at a rebuild) since the last exchange.
  void locate(const Particles& particles);
  void exchange(std::size_t per_recv, bool forward);

  MPI_Comm comm_;
  std::vector<HaloLink> links_;
  std::vector<std::vector<std::size_t>> send_index_, recv_index_;
  std::vector<std::vector<double>> send_buffer_, recv_buffer_;
  std::vector<MPI_Request> requests_;
  double seconds_ = 0;
  Times times_;
  bool barriers_ = false;
};

}  // namespace shard::mpi
