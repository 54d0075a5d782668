// The decomposed run (shard::mpi::DistributedSimulation) against the serial Simulation, started
// with mpirun on 1, 2 or 4 ranks (tests/mpi/CMakeLists.txt). A bonded block is pulled apart by two
// slabs of prescribed particles while gravity presses it onto a floor wall: bonds, Hertz-Mindlin
// contacts with history, a wall with contacts, migration and re-partitions all take part, and bonds
// break. Modes:
//   agreement  the decomposed run agrees with the serial one (rank 0 runs it) within 1e-9 of the
//              largest displacement up to the first break, breaks the same bonds in the same order,
//              and a second decomposed run is identical to the bit, as is a third started from the
//              block held by rank 0 alone (ScatteredScene)
//   scene F N [section.key=value ...]  the scene file F (e.g. the four-point bending beam) over N steps: decomposed and
//              serial agree within 1e-9 of the displacement scale and break the same bonds
//   too_many   a scene of 8 spheres on more ranks than it has cells: every rank refuses it alike
//   fragments  the block cut into five slabs of 2, 9, 1, 8 and 4 layers plus three loose spheres:
//              the distributed fragment labels (label_fragments) after 20 steps are the serial
//              labeller's on the gathered state, particle by particle, with the same sizes; on 4
//              ranks one fragment spans at least three ranks' sub-domains
// Exit code 0 on success; each failed check prints one line on rank 0.
#include <mpi.h>
#include <omp.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <memory>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "pulled_block.hpp"
#include "shard/analysis/components.hpp"
#include "shard/mpi/distributed_simulation.hpp"
#include "shard/plugin_host.hpp"
#include "shard/scene.hpp"
#include "shard/simulation.hpp"

using namespace shard;
using namespace shard::testing;

namespace {

constexpr std::int64_t kSteps = 900;

struct Outcome {
  double dt = 0;
  std::int64_t first_break = -1;  // step of the first break
  std::vector<Index> id;
  std::vector<Vec3> position, start;  // at the first break, by id
  std::vector<Quat> orientation;
  std::vector<std::array<std::int64_t, 3>> breaks;  // step, smaller id, larger id
  Vec3 wall_force = Vec3::Zero();                   // at the first break
  std::uint64_t hash = 0;                           // FNV-1a over the final state's bits, by id
  std::int64_t rebuilds = 0;                        // the serial run's neighbour-list rebuilds
  double seconds = 0;
};

std::uint64_t fnv(std::uint64_t h, const void* data, std::size_t bytes) {
  const auto* b = static_cast<const unsigned char*>(data);
  for (std::size_t k = 0; k < bytes; ++k) h = (h ^ b[k]) * 1099511628211ull;
  return h;
}

std::vector<std::array<std::int64_t, 3>> break_list(const std::vector<BondBreakEvent>& events) {
  std::vector<std::array<std::int64_t, 3>> out;
  for (const BondBreakEvent& e : events)
    out.push_back({e.step, std::min(e.id_i, e.id_j), std::max(e.id_i, e.id_j)});
  std::sort(out.begin(), out.end());
  return out;
}

Outcome serial(const Models& m) {
  const double start = MPI_Wtime();
  Simulation sim(block(m));
  Outcome o;
  o.dt = sim.dt();
  const auto snapshot = [&] {
    const Particles& p = sim.particles();
    o.id.assign(p.size(), 0);
    o.position.resize(p.size());
    o.orientation.resize(p.size());
    for (std::size_t k = 0; k < p.size(); ++k) {
      const auto i = static_cast<std::size_t>(p.id[k]);
      o.position[i] = p.position[k];
      o.orientation[i] = p.orientation[k];
    }
    o.wall_force = sim.walls()[0].force;
  };
  for (std::int64_t s = 0; s < kSteps; ++s) {
    sim.step();
    if (o.first_break < 0 && !sim.break_events().empty()) {
      o.first_break = sim.step_count();
      snapshot();
    }
  }
  o.breaks = break_list(sim.break_events());
  o.rebuilds = sim.neighbour_rebuilds();
  o.seconds = MPI_Wtime() - start;
  return o;
}

// The block on rank 0 only, the other ranks given its models, walls and settings: what a run whose
// scene rank 0 alone generated starts from (DistributedSimulation::ScatteredScene).
mpi::DistributedSimulation scattered_block(const Models& m) {
  SimulationSetup share = block(m);
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  if (rank != 0) {
    share.particles = Particles{};
    share.bonds.clear();
  }
  return mpi::DistributedSimulation(MPI_COMM_WORLD, std::move(share), mpi::DistributedSimulation::ScatteredScene{});
}

Outcome decomposed(const Models& m, double* halo_share = nullptr, std::int64_t* repartitions = nullptr,
                   bool scattered = false) {
  mpi::DistributedSimulation sim = scattered ? scattered_block(m) : mpi::DistributedSimulation(MPI_COMM_WORLD, block(m));
  Outcome o;
  o.dt = sim.dt();
  const double start = MPI_Wtime();
  for (std::int64_t s = 0; s < kSteps; ++s) {
    sim.step();
    if (o.first_break < 0 && !sim.break_events().empty()) {
      o.first_break = sim.step_count();
      const mpi::GatheredParticles g = sim.gather(0);
      o.position = g.position;
      o.orientation = g.orientation;
      o.wall_force = sim.walls()[0].force;
    }
  }
  sim.check_finite();
  const double seconds = MPI_Wtime() - start;
  if (halo_share) *halo_share = sim.halo_seconds() / seconds;
  const double partition_share = sim.partition_seconds() / seconds;
  const std::size_t owned = sim.owned(), ghosts = sim.ghosts();
  std::vector<unsigned long> counts(2 * static_cast<std::size_t>(sim.ranks()));
  const unsigned long mine[2] = {owned, ghosts};
  MPI_Gather(mine, 2, MPI_UNSIGNED_LONG, counts.data(), 2, MPI_UNSIGNED_LONG, 0, MPI_COMM_WORLD);
  if (sim.rank() == 0 && halo_share) {
    std::printf("owned/ghosts per rank:");
    for (int r = 0; r < sim.ranks(); ++r) std::printf(" %lu/%lu", counts[2 * static_cast<std::size_t>(r)], counts[2 * static_cast<std::size_t>(r) + 1]);
    std::printf("; re-partitions %.0f %% of the time\n", 100 * partition_share);
  }
  if (repartitions) *repartitions = sim.repartitions();
  o.breaks = break_list(sim.break_events());
  const mpi::GatheredParticles g = sim.gather(0);
  for (std::size_t k = 0; k < g.id.size(); ++k) {
    o.hash = fnv(o.hash, g.position[k].data(), 3 * sizeof(double));
    o.hash = fnv(o.hash, g.velocity[k].data(), 3 * sizeof(double));
    o.hash = fnv(o.hash, g.omega[k].data(), 3 * sizeof(double));
    o.hash = fnv(o.hash, g.orientation[k].coeffs().data(), 4 * sizeof(double));
  }
  return o;
}

// Rank 0 runs the serial reference while the others wait without spinning (the ranks share cores).
Outcome serial_on_root(const Models& m, int rank) {
  Outcome o;
  if (rank == 0) o = serial(m);
  MPI_Request barrier;
  MPI_Ibarrier(MPI_COMM_WORLD, &barrier);
  for (int done = 0; !done;) {
    MPI_Test(&barrier, &done, MPI_STATUS_IGNORE);
    if (!done) usleep(2000);
  }
  return o;
}

int failures = 0;
void check(bool ok, int rank, const std::string& what) {
  if (!ok) ++failures;
  if (rank == 0) std::printf("%s: %s\n", ok ? "ok  " : "FAIL", what.c_str());
}

int agreement(int rank, int ranks) {
  const Models m;
  const Outcome ref = serial_on_root(m, rank);
  double halo_share = 0;
  std::int64_t repartitions = 0;
  const double t0 = MPI_Wtime();
  const Outcome a = decomposed(m, &halo_share, &repartitions);
  const double t1 = MPI_Wtime();
  const Outcome b = decomposed(m);
  const Outcome c = decomposed(m, nullptr, nullptr, true);
  if (rank == 0) {
    std::printf("serial: %.2f s, %lld neighbour-list rebuilds\n", ref.seconds, static_cast<long long>(ref.rebuilds));
    std::printf("%d ranks: %lld steps in %.2f s (halo exchange %.0f %% of it), %lld re-partitions, first break at "
                "step %lld (serial %lld), %zu breaks (serial %zu)\n",
                ranks, static_cast<long long>(kSteps), t1 - t0, 100 * halo_share, static_cast<long long>(repartitions),
                static_cast<long long>(a.first_break), static_cast<long long>(ref.first_break), a.breaks.size(),
                ref.breaks.size());
  }
  if (rank == 0) std::printf("final state hash %016llx\n", static_cast<unsigned long long>(a.hash));
  check(a.hash == b.hash && a.breaks == b.breaks, rank, "two decomposed runs on this rank count are identical to the bit");
  check(c.hash == a.hash && c.breaks == a.breaks && !a.breaks.empty(), rank,
        "the block held by rank 0 alone and scattered by the first partition runs identically to the bit");
  if (rank == 0) {
    check(a.dt == ref.dt, rank, "the time step is the serial run's");
    check(ref.first_break > 0, rank, "the serial block breaks within the run");
    check(a.first_break == ref.first_break, rank, "the first bond breaks at the serial run's step");
    // Round-off (1e-16 per sum, summed in another order) grows little over a few hundred steps of
    // an elastic block; 1e-9 of the largest displacement separates it from a lost or doubled force.
    double scale = 0, worst = 0, turn = 0;
    for (std::size_t k = 0; k < ref.position.size() && a.position.size() == ref.position.size(); ++k) {
      worst = std::max(worst, (a.position[k] - ref.position[k]).norm());
      turn = std::max(turn, a.orientation[k].angularDistance(ref.orientation[k]));
    }
    // The largest displacement at the first break: the slabs' travel.
    scale = kSpeed * ref.dt * static_cast<double>(ref.first_break);
    std::printf("at the first break: max |dx| %.3g m over a displacement scale of %.3g m = %.3g; max turn %.3g rad; "
                "floor force %.6g N (serial %.6g N)\n",
                worst, scale, worst / scale, turn, a.wall_force.z(), ref.wall_force.z());
    check(a.position.size() == ref.position.size(), rank, "every particle gathered");
    check(worst < 1e-9 * scale, rank, "positions agree with the serial run within 1e-9 of the displacement scale");
    check(turn < 1e-9, rank, "orientations agree within 1e-9 rad");
    check(std::abs(a.wall_force.z() - ref.wall_force.z()) <= 1e-9 * std::abs(ref.wall_force.z()), rank,
          "the floor's force, summed over the ranks, is the serial one within 1e-9");
    check(ref.wall_force.z() < 0, rank, "the block presses on the floor (the wall is pushed down)");
    check(a.breaks == ref.breaks, rank, "the same bonds break at the same steps, in the same order, as in the serial run");
  }
  MPI_Bcast(&failures, 1, MPI_INT, 0, MPI_COMM_WORLD);
  return failures == 0 ? 0 : 1;
}

int too_many(int rank, int ranks) {
  const Models m;
  SimulationSetup s;
  for (int k = 0; k < 8; ++k) s.particles.add(Vec3(0.4e-3 * (k % 2), 0.4e-3 * ((k / 2) % 2), 0.4e-3 * (k / 4)), 0.5e-3, 2500.0);
  s.contact = m.contact.get();
  std::string message;
  try {
    mpi::DistributedSimulation sim(MPI_COMM_WORLD, std::move(s));
  } catch (const std::invalid_argument& e) {
    message = e.what();
  }
  if (rank == 0) std::printf("message: %s\n", message.c_str());
  const bool refused = message.find("MPI ranks cannot hold a partition") != std::string::npos &&
                       message.find("run on fewer ranks") != std::string::npos;
  int all = refused ? 1 : 0, every = 0;
  MPI_Allreduce(&all, &every, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD);
  check(ranks > 1 && every == 1, rank, "every rank refuses 8 touching spheres in one cell on several ranks, naming the fix");
  return failures == 0 ? 0 : 1;
}

// The block without the bonds across the planes after layers 1, 10, 11 and 19 (slabs of 2, 9, 1, 8
// and 4 layers: 160, 720, 80, 640 and 320 spheres, no two alike in mass) and without any bond of
// three spheres inside the slabs (equal masses: their order is the smallest id's).
SimulationSetup cut_block(const Models& m) {
  SimulationSetup s = block(m);
  const auto layer = [](Index site) { return site % kNx; };
  const std::vector<Index> loose = {(4 * kNy + 5) * kNx + 5, (3 * kNy + 2) * kNx + 15, (1 * kNy + 8) * kNx + 6};
  std::vector<std::pair<Index, Index>> kept;
  for (const auto& [a, b] : s.bonds) {
    const Index lower = std::min(layer(a), layer(b));
    const bool across = layer(a) != layer(b) && (lower == 1 || lower == 10 || lower == 11 || lower == 19);
    const bool of_loose = std::count(loose.begin(), loose.end(), a) + std::count(loose.begin(), loose.end(), b) > 0;
    if (!across && !of_loose) kept.emplace_back(a, b);
  }
  s.bonds = std::move(kept);
  return s;
}

// The serial labeller and canonical numbering on the whole state (ascending id), as a serial run's
// frame gets them.
std::vector<Index> serial_labels(const SimulationState& whole, std::vector<std::size_t>& sizes) {
  std::vector<Index> labels;
  analysis::UnionFindLabeller labeller;
  const Index count = labeller.label(whole.particles.size(), {whole.bonds.i, whole.bonds.j}, labels);
  analysis::canonicalise_labels(labels, count, whole.particles.mass, whole.particles.id);
  sizes.assign(static_cast<std::size_t>(count), 0);
  for (Index l : labels) ++sizes[static_cast<std::size_t>(l)];
  std::sort(sizes.begin(), sizes.end(), std::greater<>());
  return labels;
}

// How many ranks own particles of the fragment that spans most of them (on rank 0).
int widest_span(const mpi::DistributedSimulation& sim, const std::vector<Index>& labels) {
  std::vector<Index> present(labels);
  std::sort(present.begin(), present.end());
  present.erase(std::unique(present.begin(), present.end()), present.end());
  std::vector<Index> all = sim.gather_to_root(present);
  std::map<Index, int> ranks_of;
  for (Index l : all) ++ranks_of[l];
  int widest = 0;
  for (const auto& [label, count] : ranks_of) widest = std::max(widest, count);
  return widest;
}

int fragments(int rank, int ranks) {
  const Models m;
  mpi::DistributedSimulation sim(MPI_COMM_WORLD, cut_block(m));
  sim.run(20);
  const mpi::FragmentLabels f = sim.label_fragments();
  const mpi::FrameShare share = sim.frame_share();
  const std::vector<Index> ids = sim.gather_to_root(share.particles.id), labels = sim.gather_to_root(f.labels);
  const SimulationState whole = sim.gather_state(0, false);
  const int widest = widest_span(sim, f.labels);
  if (rank == 0) {
    std::vector<std::size_t> sizes;
    const std::vector<Index> reference = serial_labels(whole, sizes);
    std::map<Index, Index> by_id;
    for (std::size_t k = 0; k < ids.size(); ++k) by_id[ids[k]] = labels[k];
    std::size_t same = 0;
    for (std::size_t k = 0; k < whole.particles.size(); ++k) {
      const auto it = by_id.find(whole.particles.id[k]);
      same += it != by_id.end() && it->second == reference[k] ? 1 : 0;
    }
    std::printf("%d ranks: %zu fragments (sizes", ranks, f.sizes.size());
    for (std::size_t n : f.sizes) std::printf(" %zu", n);
    std::printf("), %d exchange rounds, the widest over %d ranks; %zu of %zu labels as the serial labeller's\n",
                f.rounds, widest, same, whole.particles.size());
    check(ids.size() == whole.particles.size() && same == ids.size(), rank,
          "every particle's fragment label is the serial labeller's");
    check(f.sizes == sizes && sizes.size() == 8, rank, "eight fragments, of the serial labeller's sizes");
    check(ranks < 4 || widest >= 3, rank, "on 4 ranks a fragment spans at least three ranks' sub-domains");
  }
  MPI_Bcast(&failures, 1, MPI_INT, 0, MPI_COMM_WORLD);
  return failures == 0 ? 0 : 1;
}

int scene_run(int rank, int ranks, const std::string& file, std::int64_t steps, const std::vector<std::string>& overrides) {
  PluginHost host;
  host.load_directories(PluginHost::default_search_path());
  const Scene scene = load_scene(std::filesystem::path(file), overrides, host);
  SceneInstance inst = instantiate(scene, host, nullptr);
  Simulation& serial_sim = *inst.simulation;
  std::vector<Vec3> start(serial_sim.particles().size());
  for (std::size_t k = 0; k < start.size(); ++k)
    start[static_cast<std::size_t>(serial_sim.particles().id[k])] = serial_sim.particles().position[k];
  mpi::DistributedSimulation sim(MPI_COMM_WORLD, setup_of(scene, inst));
  const double t0 = MPI_Wtime();
  sim.run(steps);
  const double t1 = MPI_Wtime();
  const mpi::GatheredParticles g = sim.gather(0);
  const auto breaks = break_list(sim.break_events());
  std::vector<Vec3> wall_force;
  for (const Wall& w : sim.walls()) wall_force.push_back(w.force);
  if (rank == 0) {  // the serial run after the decomposed one: the other ranks wait in MPI_Finalize
    // SHARD_SERIAL_THREADS: the serial reference on another OpenMP team (how far thread counts
    // alone move the run apart).
    if (const char* t = std::getenv("SHARD_SERIAL_THREADS")) omp_set_num_threads(std::atoi(t));
    serial_sim.run(steps);
    const Particles& p = serial_sim.particles();
    double worst = 0, scale = 0;
    std::vector<Vec3> ref(p.size());
    for (std::size_t k = 0; k < p.size(); ++k) ref[static_cast<std::size_t>(p.id[k])] = p.position[k];
    for (std::size_t k = 0; k < ref.size() && g.position.size() == ref.size(); ++k) {
      worst = std::max(worst, (g.position[k] - ref[k]).norm());
      scale = std::max(scale, (ref[k] - start[k]).norm());
    }
    // The displacement scale: the largest of the particles' displacements and the walls' travel
    // (the imposed loading; while the pins only start pressing it is the larger one).
    for (const Wall& w : serial_sim.walls()) scale = std::max(scale, w.displacement.norm());
    double force_gap = 0, force_scale = 0;
    for (std::size_t w = 0; w < wall_force.size(); ++w) {
      force_gap = std::max(force_gap, (wall_force[w] - serial_sim.walls()[w].force).norm());
      force_scale = std::max(force_scale, serial_sim.walls()[w].force.norm());
    }
    std::printf("dt %.3g s; %s on %d ranks: %zu particles, %lld steps in %.2f s (halo %.0f %%, re-partitions %lld); max |dx| %.3g "
                "of a displacement scale %.3g m; wall forces within %.3g of %.3g N; %zu breaks (serial %zu)\n",
                sim.dt(), file.c_str(), ranks, g.id.size(), static_cast<long long>(steps), t1 - t0,
                100 * sim.halo_seconds() / (t1 - t0), static_cast<long long>(sim.repartitions()), worst, scale, force_gap,
                force_scale, breaks.size(), serial_sim.break_events().size());
    check(g.position.size() == ref.size(), rank, "every particle gathered");
    check(scale > 0 && worst < 1e-9 * scale, rank, "positions agree with the serial run within 1e-9 of the displacement scale");
    check(force_scale > 0 && force_gap <= 1e-9 * force_scale, rank, "the walls' forces agree within 1e-9");
    check(breaks == break_list(serial_sim.break_events()), rank, "the same bonds break at the same steps");
  }
  MPI_Bcast(&failures, 1, MPI_INT, 0, MPI_COMM_WORLD);
  return failures == 0 ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
  MPI_Init(&argc, &argv);
  int rank = 0, ranks = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &ranks);
  const std::string mode = argc > 1 ? argv[1] : "agreement";
  int code = 2;
  try {
    if (mode == "agreement") code = agreement(rank, ranks);
    if (mode == "too_many") code = too_many(rank, ranks);
    if (mode == "fragments") code = fragments(rank, ranks);
    if (mode == "scene" && argc > 3) code = scene_run(rank, ranks, argv[2], std::stoll(argv[3]), std::vector<std::string>(argv + 4, argv + argc));
  } catch (const std::exception& e) {
    std::fprintf(stderr, "rank %d: %s\n", rank, e.what());
    MPI_Abort(MPI_COMM_WORLD, 3);
  }
  MPI_Finalize();
  return code;
}
