// The run-to-rest rule ([stop] rest_speed) and the first wall impact of every body (/body_impacts)
// in `shard run` decomposed over MPI ranks (driver::run_distributed), against the serial driver, on
// tests/mpi/drops.toml: three bonded rafts dropped onto a floor, one thrown against a side wall
// first, run until every sphere stayed slower than 0.01 m/s for 0.01 s. Modes:
//   serial OUT               the reference: driver::run, no MPI; checks the scene does what it says
//                            (stops at rest, every body hit, the thrown one on the side wall first,
//                            the impacts at different steps)
//   decomposed OUT REF       mpirun -np N: the same run decomposed; every rank stops at rest at the
//                            reference's step, and rank 0's run file holds the reference's
//                            /body_impacts (below)
//   interrupt OUT STEP       mpirun -np N: the run stopped at STEP (checkpoint written)
//   restart OUT REF          mpirun -np M: continues OUT to rest and compares as `decomposed`
// The impacts must agree in hit, step and wall exactly (the steps are the same whatever the
// partition: the same contacts begin at the same step), in time within 1e-12 s (the same sums of
// dt), in normal within 1e-12 (a plane's), and in velocity within 1e-9 of the speed (the sum of
// the body's momenta is taken in another order over the ranks: round-off only; the load-curve
// agreement of test_mpi_run allows the same 1e-9).
#include <fmt/format.h>
#include <hdf5.h>
#include <mpi.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <set>
#include <string>
#include <vector>

#include "shard/domain_exchange.hpp"
#include "shard/driver/checkpoint_writer.hpp"
#include "shard/driver/distributed_run.hpp"
#include "shard/driver/run_driver.hpp"
#include "shard/driver/scene_rules.hpp"
#include "shard/driver/stop_rules.hpp"
#include "shard/plugin_host.hpp"
#include "shard/run_file.hpp"

using namespace shard;
namespace fs = std::filesystem;

namespace {

int failures = 0;
int rank_ = 0;
void check(bool ok, const std::string& what) {
  if (!ok) ++failures;
  if (rank_ == 0) std::printf("%s: %s\n", ok ? "ok  " : "FAIL", what.c_str());
}

driver::RunSpec spec_for(const fs::path& out) {
  driver::RunSpec spec;
  spec.scene = fs::path(SHARD_SOURCE_DIR) / "tests" / "mpi" / "drops.toml";
  spec.out_dir = out;
  spec.threads = 1;
  return spec;
}

struct Observers {
  driver::SceneRules rules;
  driver::CheckpointWriter checkpoints{0};
  driver::InterruptStop interrupt;
  explicit Observers(std::int64_t at_step = -1) : interrupt(at_step) {}
  std::vector<driver::RunObserver*> list() {
    auto l = rules.observers();
    l.insert(l.end(), {&checkpoints, &interrupt});
    return l;
  }
};

constexpr std::size_t kRafts = 3;

// How the decomposition placed the rafts when the loop began: the ranks that own spheres and the
// rafts whose spheres lie on more than one rank (their impact velocity is a sum over ranks).
class PartitionLog : public driver::RunObserver {
 public:
  int ranks_owning = 0, bodies_split = 0;
  void on_start(driver::RunState& run) override {
    const Particles& p = run.sim.particles();
    int size = 1;
    MPI_Comm_size(MPI_COMM_WORLD, &size);
    std::vector<int> mine(kRafts, 0), all(kRafts * static_cast<std::size_t>(size));
    int owned = 0;
    for (std::size_t k = 0; k < p.size(); ++k)
      if (!(p.flags[k] & kGhost)) {
        ++owned;
        mine.at(static_cast<std::size_t>(p.body[k])) = 1;
      }
    MPI_Allgather(mine.data(), kRafts, MPI_INT, all.data(), kRafts, MPI_INT, MPI_COMM_WORLD);
    int any = owned > 0 ? 1 : 0;
    MPI_Allreduce(&any, &ranks_owning, 1, MPI_INT, MPI_SUM, MPI_COMM_WORLD);
    for (std::size_t b = 0; b < kRafts; ++b) {
      int holders = 0;
      for (int r = 0; r < size; ++r) holders += all[kRafts * static_cast<std::size_t>(r) + b];
      bodies_split += holders > 1 ? 1 : 0;
    }
  }
};

driver::RunResult run(const driver::RunSpec& spec, bool decomposed, std::int64_t at_step = -1,
                      PartitionLog* partition = nullptr) {
  PluginHost host;
  host.load_directories({fs::path(SHARD_BUILD_DIR) / "plugins"});
  Observers o(at_step);
  auto list = o.list();
  if (partition) list.push_back(partition);
  return decomposed ? driver::run_distributed(spec, host, list) : driver::run(spec, host, list);
}

void print_impacts(const std::vector<BodyImpact>& impacts, const std::string& who) {
  if (rank_ != 0) return;
  for (std::size_t b = 0; b < impacts.size(); ++b) {
    const BodyImpact& i = impacts[b];
    std::printf("%s: body %zu %s step %lld t %.6g s wall %d speed %.6g m/s angle %.4g deg\n", who.c_str(), b,
                i.hit ? "hit" : "never hit", static_cast<long long>(i.step), i.time, i.wall, i.speed(),
                i.angle_degrees());
  }
}

// The run ended at rest (on every rank, at the reference's step) with the reference's impacts.
void compare(const driver::RunResult& r, const fs::path& file, const fs::path& reference, const std::string& who) {
  int at_rest = r.stop == driver::StopReason::Rest ? 1 : 0, all_at_rest = 0;
  MPI_Allreduce(&at_rest, &all_at_rest, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD);
  check(all_at_rest == 1, who + ": every rank stops the run at rest (" + r.stop_reason + ")");
  long long steps[2] = {static_cast<long long>(r.steps), -static_cast<long long>(r.steps)}, extremes[2] = {0, 0};
  MPI_Allreduce(steps, extremes, 2, MPI_LONG_LONG, MPI_MAX, MPI_COMM_WORLD);
  check(extremes[0] == -extremes[1], who + ": every rank stops at the same step");
  if (rank_ != 0) return;
  const RunFile a(file), b(reference);
  const auto sa = a.read_integer_series("step"), sb = b.read_integer_series("step");
  std::printf("%s: stopped at step %lld (reference %lld)\n", who.c_str(), static_cast<long long>(r.steps),
              static_cast<long long>(sb.back()));
  check(r.steps == sb.back(), who + ": the run stops at the serial run's step");
  check(sa == sb, who + ": the same series rows (steps)");
  // The walls' own impact counters (contacts begun, the wear indicator), counted by each rank for
  // its own spheres and summed in each series row.
  bool same_counts = true;
  for (const char* wall : {"side", "floor"}) {
    const auto ca = a.read_wall_impacts(wall), cb = b.read_wall_impacts(wall);
    same_counts = same_counts && ca == cb;
    std::printf("%s: wall %s: %lld impacts (reference %lld)\n", who.c_str(), wall,
                static_cast<long long>(ca.empty() ? -1 : ca.back()), static_cast<long long>(cb.empty() ? -1 : cb.back()));
  }
  check(same_counts, who + ": every series row counts the walls' impacts as the serial run does");
  const auto ia = a.read_body_impacts(), ib = b.read_body_impacts();
  print_impacts(ia, who);
  check(ia.size() == ib.size() && !ib.empty(), who + ": a /body_impacts record for every body");
  bool same_hits = ia.size() == ib.size();
  double worst_t = 0, worst_n = 0, worst_v = 0;
  for (std::size_t k = 0; same_hits && k < ia.size(); ++k) {
    same_hits = ia[k].hit == ib[k].hit && ia[k].step == ib[k].step && ia[k].wall == ib[k].wall;
    worst_t = std::max(worst_t, std::abs(ia[k].time - ib[k].time));
    worst_n = std::max(worst_n, (ia[k].normal - ib[k].normal).norm());
    worst_v = std::max(worst_v, (ia[k].velocity - ib[k].velocity).norm() / std::max(ib[k].speed(), 1e-300));
  }
  std::printf("%s: impacts |dt| %.3g s, |d normal| %.3g, |d velocity| / speed %.3g\n", who.c_str(), worst_t, worst_n,
              worst_v);
  check(same_hits, who + ": every body hit at the same step on the same wall");
  check(worst_t <= 1e-12 && worst_n <= 1e-12, who + ": the same impact times and normals");
  check(worst_v <= 1e-9, who + ": the impact velocities agree within 1e-9 of the speed");
}

}  // namespace

int main(int argc, char** argv) {
  H5dont_atexit();
  if (argc < 3) {
    std::fprintf(stderr, "usage: test_mpi_drops serial|decomposed|interrupt|restart OUT [REF|STEP]\n");
    return 2;
  }
  const std::string mode = argv[1];
  const fs::path out = argv[2];
  if (mode == "serial") {
    fs::remove_all(out);
    const driver::RunResult r = run(spec_for(out), false);
    std::printf("serial: %lld steps (t = %.6g s), %s\n", static_cast<long long>(r.steps), r.time,
                r.stop_reason.c_str());
    check(r.stop == driver::StopReason::Rest, "the serial run stops at rest before its duration");
    const auto impacts = RunFile(out / "run.h5").read_body_impacts();
    print_impacts(impacts, "serial");
    check(impacts.size() == kRafts, "three bodies");
    std::set<std::int64_t> steps;
    bool all_hit = true;
    for (const BodyImpact& i : impacts) {
      all_hit = all_hit && i.hit;
      steps.insert(i.step);
    }
    check(all_hit, "every body hits a wall");
    check(steps.size() == impacts.size(), "the bodies hit at different steps");
    check(impacts.size() == kRafts && impacts[0].wall == 0 && impacts[1].wall == 1 && impacts[2].wall == 1,
          "the thrown raft hits the side wall first, the others the floor");
    return failures > 0 ? 1 : 0;
  }
  const driver::MpiSession mpi;
  rank_ = mpi.rank();
  const std::string who = fmt::format("{} ranks", mpi.size());
  try {
    if (mode == "decomposed" && argc > 3) {
      if (rank_ == 0) fs::remove_all(out);
      MPI_Barrier(MPI_COMM_WORLD);
      PartitionLog partition;
      const driver::RunResult r = run(spec_for(out), true, -1, &partition);
      if (rank_ == 0)
        std::printf("%s: %d ranks own spheres at the start; %d of the %zu rafts lie on more than one rank\n",
                    who.c_str(), partition.ranks_owning, partition.bodies_split, kRafts);
      check(partition.ranks_owning == mpi.size(), who + ": every rank owns spheres");
      if (mpi.size() > static_cast<int>(kRafts))
        check(partition.bodies_split > 0, who + ": a raft lies on two ranks (more ranks than rafts)");
      compare(r, out / "run.h5", fs::path(argv[3]) / "run.h5", who);
    } else if (mode == "interrupt" && argc > 3) {
      if (rank_ == 0) fs::remove_all(out);
      MPI_Barrier(MPI_COMM_WORLD);
      const driver::RunResult r = run(spec_for(out), true, std::stoll(argv[3]));
      check(r.stop == driver::StopReason::Interrupted && r.steps == std::stoll(argv[3]),
            fmt::format("{}: stopped at step {} with a checkpoint", who, argv[3]));
    } else if (mode == "restart" && argc > 3) {
      driver::RunSpec spec = spec_for(out);
      spec.restart = out / "run.h5";
      const driver::RunResult r = run(spec, true);
      compare(r, out / "run.h5", fs::path(argv[3]) / "run.h5", who + " (restarted)");
    } else {
      std::fprintf(stderr, "unknown mode %s\n", mode.c_str());
      return 2;
    }
  } catch (const std::exception& e) {
    std::printf("rank %d: FAIL: %s\n", rank_, e.what());
    MPI_Abort(MPI_COMM_WORLD, 1);
  }
  int any = failures;
  MPI_Allreduce(&failures, &any, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD);
  return any > 0 ? 1 : 0;
}
