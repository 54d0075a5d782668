// A scene of several materials (tests/mpi/materials.toml: two bonded rafts of two materials thrown
// onto a rubber and a steel wall, each pair with its own friction and restitution) in `shard run`
// decomposed over MPI ranks (driver::run_distributed) against the serial driver. Modes:
//   serial OUT           the reference: driver::run, no MPI; checks the scene does what it says
//                        (bonds break, the cake raft hits the side wall, the ore raft the floor)
//   decomposed OUT REF   mpirun -np N: the same run decomposed; rank 0 compares OUT with REF
// What must agree, and how closely:
//  - the same bonds break at the same steps in the same order, the same series rows, the same first
//    impact (step, wall) of each raft: exact. A decomposed run computes every pair and bond once,
//    with the same law and the same operands, and differs from the serial one only in the order
//    in which forces are summed, so only a force within round-off of a bond's strength could
//    break it at another step;
//  - the walls' forces in every series row within 1e-9 of the largest wall force of the run
//    (test_mpi_run's bound for its load curve). Summing in another order is round-off, which the
//    landings and breaks amplify: measured 1.6e-12 of the largest force on 2 ranks, none on 1.
// A decomposed set-up that lost the material table would give every contact one law: on this
// scene its energy at step 0 is already 0.26 J above the serial run's, and the health watch stops
// it there.
#include <fmt/format.h>
#include <hdf5.h>
#include <mpi.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "shard/driver/distributed_run.hpp"
#include "shard/driver/run_driver.hpp"
#include "shard/driver/scene_rules.hpp"
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

driver::RunResult run(const fs::path& out, bool decomposed) {
  driver::RunSpec spec;
  spec.scene = fs::path(SHARD_SOURCE_DIR) / "tests" / "mpi" / "materials.toml";
  spec.out_dir = out;
  spec.threads = 1;
  PluginHost host;
  host.load_directories({fs::path(SHARD_BUILD_DIR) / "plugins"});
  driver::SceneRules rules;
  const auto observers = rules.observers();
  return decomposed ? driver::run_distributed(spec, host, observers) : driver::run(spec, host, observers);
}

constexpr const char* kWalls[] = {"side", "floor"};

// The scene does what its header says.
void check_reference(const fs::path& file) {
  const RunFile f(file);
  const auto events = f.read_break_events();
  const auto impacts = f.read_body_impacts();
  std::printf("serial: %zu bonds broken, the first at step %lld\n", events.size(),
              static_cast<long long>(events.empty() ? -1 : events.front().step));
  check(!events.empty(), "the landings break bonds");
  check(impacts.size() == 2 && impacts[0].hit && impacts[0].wall == 0, "the cake raft hits the rubber side wall first");
  check(impacts.size() == 2 && impacts[1].hit && impacts[1].wall == 1, "the ore raft hits the steel floor first");
}

void compare_breaks(const RunFile& a, const RunFile& b, const std::string& who) {
  const auto ea = a.read_break_events(), eb = b.read_break_events();
  bool same = ea.size() == eb.size() && !eb.empty();
  for (std::size_t k = 0; same && k < ea.size(); ++k)
    same = ea[k].step == eb[k].step && ea[k].id_i == eb[k].id_i && ea[k].id_j == eb[k].id_j;
  std::printf("%s: %zu bonds broken (reference %zu)\n", who.c_str(), ea.size(), eb.size());
  check(same, who + ": the same bonds break at the same steps in the same order");
  const auto ia = a.read_body_impacts(), ib = b.read_body_impacts();
  bool same_impacts = ia.size() == ib.size();
  for (std::size_t k = 0; same_impacts && k < ia.size(); ++k)
    same_impacts = ia[k].hit == ib[k].hit && ia[k].step == ib[k].step && ia[k].wall == ib[k].wall;
  check(same_impacts, who + ": each raft first hits the same wall at the same step");
}

void compare_wall_forces(const RunFile& a, const RunFile& b, const std::string& who) {
  const auto sa = a.read_integer_series("step"), sb = b.read_integer_series("step");
  check(sa == sb && !sb.empty(), who + ": the same series rows (steps)");
  if (sa != sb) return;
  double peak = 0, worst = 0;
  for (const char* wall : kWalls) {
    const auto fa = a.read_wall_series(wall, "force"), fb = b.read_wall_series(wall, "force");
    for (std::size_t k = 0; k < fb.size() && k < fa.size(); ++k) {
      peak = std::max(peak, fb[k].norm());
      worst = std::max(worst, (fa[k] - fb[k]).norm());
    }
  }
  std::printf("%s: largest wall force %.6g N, largest difference %.3g N (%.3g of it)\n", who.c_str(), peak, worst,
              worst / std::max(peak, 1e-300));
  check(peak > 0, who + ": the walls carry load");
  check(worst <= 1e-9 * peak, who + ": every wall force agrees within 1e-9 of the largest");
}

}  // namespace

int main(int argc, char** argv) {
  H5dont_atexit();
  if (argc < 3) {
    std::fprintf(stderr, "usage: test_mpi_materials serial OUT | decomposed OUT REF\n");
    return 2;
  }
  const std::string mode = argv[1];
  const fs::path out = argv[2];
  if (mode == "serial") {
    fs::remove_all(out);
    run(out, false);
    check_reference(out / "run.h5");
    return failures > 0 ? 1 : 0;
  }
  const driver::MpiSession mpi;
  rank_ = mpi.rank();
  const std::string who = fmt::format("{} ranks", mpi.size());
  if (mode != "decomposed" || argc < 4) {
    if (rank_ == 0) std::fprintf(stderr, "unknown mode %s\n", mode.c_str());
    return 2;
  }
  try {
    if (rank_ == 0) fs::remove_all(out);
    MPI_Barrier(MPI_COMM_WORLD);
    run(out, true);
    if (rank_ == 0) {
      const RunFile a(out / "run.h5"), b(fs::path(argv[3]) / "run.h5");
      compare_breaks(a, b, who);
      compare_wall_forces(a, b, who);
    }
  } catch (const std::exception& e) {
    std::printf("rank %d: FAIL: %s\n", rank_, e.what());
    MPI_Abort(MPI_COMM_WORLD, 1);
  }
  int any = failures;
  MPI_Allreduce(&failures, &any, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD);
  return any > 0 ? 1 : 0;
}
