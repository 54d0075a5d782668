// What a re-partition moves (shard::mpi::DistributedSimulation::repartition), on the pulled block
// (pulled_block.hpp) under mpirun on 1, 2 or 4 ranks: each rank keeps what it still owns and sends
// only the particles whose owner changed, with the bonds and touching contacts they own. Checked
// against ownership gathered before and after each re-partition:
//   - every particle is owned by exactly one rank, and every bond is held by the owner of its end
//     with the smaller id;
//   - after a re-partition in which k particles changed owner, the ranks sent exactly k particles,
//     as many bonds as changed holder and as many touching contacts as changed owner;
//   - a second re-partition at once (same positions and costs) moves nothing;
//   - the same over the re-partitions a 500-step run makes by itself, some particle moving on
//     more than one rank.
// Exit code 0 on success; each failed check prints one line on rank 0.
#include <mpi.h>

#include <cstdio>
#include <string>
#include <vector>

#include "pulled_block.hpp"
#include "shard/checkpoint.hpp"
#include "shard/mpi/distributed_simulation.hpp"

using namespace shard;
using namespace shard::testing;

namespace {

int failures = 0;
void check(bool ok, int rank, const std::string& what) {
  if (!ok) ++failures;
  if (rank == 0) std::printf("%s: %s\n", ok ? "ok  " : "FAIL", what.c_str());
}

// Each particle's owner by id, the same on every rank (-1: owned by none). `once`: every particle
// is owned by exactly one rank.
std::vector<int> owners(const mpi::DistributedSimulation& sim, std::size_t n, bool& once) {
  const Particles& p = sim.local().particles();
  std::vector<double> mine;
  for (std::size_t k = 0; k < p.size(); ++k)
    if (sim.owns(k)) mine.insert(mine.end(), {static_cast<double>(p.id[k]), static_cast<double>(sim.rank())});
  const std::vector<double> all = sim.gather_over_ranks(mine);
  std::vector<int> owner(n, -1);
  once = all.size() == 2 * n;
  for (std::size_t k = 0; k + 1 < all.size(); k += 2) {
    const auto id = static_cast<std::size_t>(all[k]);
    once = once && id < n && owner[id] < 0;
    if (id < n) owner[id] = static_cast<int>(all[k + 1]);
  }
  return owner;
}

// The particle (smaller id) that owns each bond and each touching contact this rank holds, gathered.
struct Holdings {
  std::vector<double> bonds, contacts;  // (owning id, holder rank) pairs
};

Holdings holdings(const mpi::DistributedSimulation& sim) {
  const Particles& p = sim.local().particles();
  const Bonds& b = sim.local().bonds();
  const double rank = sim.rank();
  Holdings mine;
  for (std::size_t k = 0; k < b.size(); ++k) {
    const Index i = p.id[static_cast<std::size_t>(b.i[k])], j = p.id[static_cast<std::size_t>(b.j[k])];
    mine.bonds.insert(mine.bonds.end(), {static_cast<double>(std::min(i, j)), rank});
  }
  const NeighbourState list = sim.local().export_state().neighbours;
  for (std::size_t k = 0; k < list.first.size(); ++k)
    if (list.touching[k])
      mine.contacts.insert(mine.contacts.end(), {static_cast<double>(p.id[static_cast<std::size_t>(list.first[k])]), rank});
  return {sim.gather_over_ranks(mine.bonds), sim.gather_over_ranks(mine.contacts)};
}

// How many of the (owning id, holder) pairs changed owner since `before`; `held_by_owner`: each
// is held by its owning particle's owner now.
std::size_t changed(const std::vector<double>& pairs, const std::vector<int>& before, const std::vector<int>& now,
                    bool& held_by_owner) {
  std::size_t moved = 0;
  for (std::size_t k = 0; k + 1 < pairs.size(); k += 2) {
    const auto id = static_cast<std::size_t>(pairs[k]);
    held_by_owner = held_by_owner && now[id] == static_cast<int>(pairs[k + 1]);
    moved += before[id] != now[id] ? 1 : 0;
  }
  return moved;
}

// Checks one re-partition (ownership `before` it) against what the ranks sent; returns the number
// of particles that changed owner.
std::size_t check_moves(const mpi::DistributedSimulation& sim, const std::vector<int>& before, std::vector<int>& now,
                        const char* which, bool quiet) {
  bool once = false;
  now = owners(sim, before.size(), once);
  std::size_t k = 0;
  for (std::size_t id = 0; id < now.size(); ++id) k += before[id] != now[id] ? 1 : 0;
  const Holdings h = holdings(sim);
  bool held = true;
  const std::size_t bonds = changed(h.bonds, before, now, held), contacts = changed(h.contacts, before, now, held);
  const mpi::DistributedSimulation::Migration& m = sim.last_migration();
  const std::vector<double> sent = sim.sum_over_ranks(
      {static_cast<double>(m.particles), static_cast<double>(m.bonds), static_cast<double>(m.contacts)});
  const bool exact = sent[0] == static_cast<double>(k) && sent[1] == static_cast<double>(bonds) &&
                     sent[2] == static_cast<double>(contacts);
  if (sim.rank() == 0 && (!quiet || !exact || !once || !held))
    std::printf("%s (step %lld): %zu particles, %zu bonds, %zu touching contacts changed owner; sent %.0f, %.0f, %.0f\n",
                which, static_cast<long long>(sim.step_count()), k, bonds, contacts, sent[0], sent[1], sent[2]);
  if (!quiet || !exact || !once || !held) {
    check(once, sim.rank(), std::string(which) + ": every particle owned by exactly one rank");
    check(held, sim.rank(), std::string(which) + ": every bond and contact held by the owner of its smaller id");
    check(exact, sim.rank(), std::string(which) + ": exactly what changed owner travelled");
  }
  return k;
}

int migration(int rank, int ranks) {
  const Models m;
  mpi::DistributedSimulation sim(MPI_COMM_WORLD, block(m));
  const std::size_t n = kNx * kNy * kNz;
  bool once = false;
  std::vector<int> before = owners(sim, n, once), now;
  check(once, rank, "after the first partition every particle is owned by exactly one rank");

  // The first partition counted no contacts (a new scene has none); the force pass made some, so a
  // re-partition now may move range ends. Right after it the same cut comes out: nothing moves.
  sim.repartition();
  check_moves(sim, before, now, "re-partition at step 0", false);
  before = now;
  sim.repartition();
  const std::size_t again = check_moves(sim, before, now, "the same re-partition again", false);
  const mpi::DistributedSimulation::Migration& last = sim.last_migration();
  const std::vector<double> sent = sim.sum_over_ranks(
      {static_cast<double>(last.particles), static_cast<double>(last.bonds), static_cast<double>(last.contacts)});
  check(again == 0 && sent[0] == 0 && sent[1] == 0 && sent[2] == 0, rank,
        "a re-partition in which no particle changes owner sends no particle, bond or contact");

  // The run's own re-partitions.
  before = now;
  std::size_t moved = 0, repartitions = 0;
  const int failed_before = failures;
  for (int s = 0; s < 500; ++s) {
    const std::int64_t count = sim.repartitions();
    sim.step();
    if (sim.repartitions() == count) continue;
    moved += check_moves(sim, before, now, "a re-partition of the run", true);
    ++repartitions;
    before = now;
  }
  if (rank == 0)
    std::printf("%d ranks: %zu re-partitions in 500 steps moved %zu particles in all (%zu sent by this rank)\n", ranks,
                repartitions, moved, sim.migration_total().particles);
  check(failures == failed_before && repartitions > 0, rank,
        "at each of the run's re-partitions exactly the particles, bonds and contacts that changed owner travelled");
  check(ranks == 1 ? moved == 0 : moved > 0, rank,
        ranks == 1 ? "on one rank no particle ever moves" : "particles changed owner during the run");
  MPI_Bcast(&failures, 1, MPI_INT, 0, MPI_COMM_WORLD);
  return failures == 0 ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
  MPI_Init(&argc, &argv);
  int rank = 0, ranks = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &ranks);
  int code = 2;
  try {
    code = migration(rank, ranks);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "rank %d: %s\n", rank, e.what());
    MPI_Abort(MPI_COMM_WORLD, 3);
  }
  MPI_Finalize();
  return code;
}
