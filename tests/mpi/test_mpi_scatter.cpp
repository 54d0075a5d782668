// The set-up of `mpirun -np N shard run` (the driver's MPI backend, driver/src/mpi/mpi_backend.cpp)
// on tests/mpi/materials.toml (two bonded bodies of two materials): rank 0 alone generates the
// scene and holds it whole; every other rank builds the models only and never holds more particles
// than its share. Checked on every rank, exactly (counts and bit patterns, nothing rounded):
//  - after instantiating: rank 0 holds the whole scene's Simulation and packing; any other rank
//    holds no Simulation and no particle (its models: a contact law with the scene's materials);
//  - the whole scene's figures (WholeScene: particle count, dt, time-step limits, packing quality,
//    body count, the energy watch's baseline) are on every rank bit for bit what the serial
//    backend computes from the whole scene (but for the generator's own timing);
//  - after the start: the ranks own every particle exactly once, and a rank other than 0 holds
//    (owned and ghost copies) fewer particles than the whole scene.
// With the arguments `overlap DIR`: three spheres, two generated inside one another, blow up
// within 20 steps (tests/reliability's serial case); the initial packing is on rank 0 alone, and
// every rank's NumericalError still names the overlap (rank 0 finds it and shares its figures).
// A decomposed run's results against the serial run are test_mpi_run's, test_mpi_drops' and
// test_mpi_materials'.
#include <mpi.h>

#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "../common/overlap_scene.hpp"
#include "mpi/mpi_backend.hpp"
#include "serial_backend.hpp"
#include "shard/driver/distributed_run.hpp"
#include "shard/driver/numerical_health.hpp"
#include "shard/driver/run_driver.hpp"
#include "shard/plugin_host.hpp"
#include "shard/scene.hpp"

using namespace shard;
using namespace shard::driver::detail;
namespace fs = std::filesystem;

namespace {

int failures = 0;
int rank_ = 0;

// Every rank's verdict; rank 0 prints whether all passed.
void check(bool ok, const std::string& what) {
  int mine = ok ? 1 : 0, all = 0;
  MPI_Allreduce(&mine, &all, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD);
  if (!all) ++failures;
  if (!ok) std::printf("rank %d: FAIL: %s\n", rank_, what.c_str());
  if (rank_ == 0) std::printf("%s: %s\n", all ? "ok  " : "FAIL", what.c_str());
}

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

bool same(const WholeScene& a, const WholeScene& b) {
  bool ok = a.particles == b.particles && same_bits(a.dt, b.dt) && a.bodies.bodies == b.bodies.bodies &&
            a.bodies.known == b.bodies.known && same_bits(a.energy0, b.energy0) &&
            same_bits(a.potential0, b.potential0) && same_bits(a.energy_scale, b.energy_scale) &&
            a.limits.size() == b.limits.size() && a.quality.size() == b.quality.size();
  for (std::size_t k = 0; ok && k < a.limits.size(); ++k)
    ok = a.limits[k].name == b.limits[k].name && same_bits(a.limits[k].critical, b.limits[k].critical) &&
         same_bits(a.limits[k].recommended, b.limits[k].recommended);
  // A generator's own timing ("generation_seconds") differs between two generations of one scene.
  const auto timing = [](const std::string& name) { return name.ends_with("_seconds"); };
  for (std::size_t k = 0; ok && k < a.quality.size(); ++k)
    ok = a.quality[k].first == b.quality[k].first &&
         (timing(a.quality[k].first) || same_bits(a.quality[k].second, b.quality[k].second));
  return ok;
}

// The packing's overlap (tests/common/overlap_scene.hpp) is found on rank 0, which alone holds it.
void overlap(const fs::path& dir, const PluginHost& host) {
  if (rank_ == 0) {
    fs::remove_all(dir);
    fs::create_directories(dir);
    test::write_overlap_scene(dir);
  }
  MPI_Barrier(MPI_COMM_WORLD);
  driver::RunSpec spec;
  spec.scene = dir / "scene.toml";
  spec.out_dir = dir;
  spec.threads = 1;
  std::string message;
  try {
    driver::run_distributed(spec, host, {});
  } catch (const NumericalError& e) {
    message = e.what();
  }
  std::printf("rank %d: %s\n", rank_, message.c_str());
  check(message.find("overlapping initial packing: particles 0 and 1 overlapped by 190 %") != std::string::npos,
        "every rank's blow-up names the overlapping initial packing that rank 0 alone holds");
}

}  // namespace

int main(int argc, char** argv) {
  const driver::MpiSession mpi;
  rank_ = mpi.rank();
  PluginHost host;
  host.load_directories({fs::path(SHARD_BUILD_DIR) / "plugins"});
  if (argc > 2 && std::string(argv[1]) == "overlap") {
    overlap(argv[2], host);
    return failures > 0 ? 1 : 0;
  }
  const Scene scene = load_scene(fs::path(SHARD_SOURCE_DIR) / "tests" / "mpi" / "materials.toml", host);
  // The reference: what a serial run reads of the whole scene (every rank makes it here, for the
  // test only; the scene is small).
  const ScenePart serial = SerialBackend().instantiate(scene, host, {});
  const std::size_t whole = serial.whole.particles;

  MpiBackend backend;
  ScenePart part = backend.instantiate(scene, host, {});
  const Simulation* sim = part.instance.simulation.get();
  const std::size_t held = sim ? sim->particles().size() : 0;
  const std::size_t packed = part.instance.body.position.size();
  std::printf("rank %d: %zu particles held after instantiating, %zu in its packing (whole scene %zu)\n", rank_, held,
              packed, whole);
  check(whole > 0 && serial.whole.bodies.bodies == 2, "the scene has particles in two bodies");
  const bool as_it_should = rank_ == 0 ? held == whole && packed == whole
                                       : !sim && packed == 0 && part.instance.contact && part.instance.bond;
  check(as_it_should, "after instantiating rank 0 holds the whole scene, any other rank no particle (the models only)");
  check(same(part.whole, serial.whole), "every rank's whole-scene figures are bit for bit the serial backend's");

  backend.start(scene, part, nullptr);
  const Particles& local = backend.local().particles();
  std::size_t owned = 0;
  for (std::size_t k = 0; k < local.size(); ++k) owned += backend.owns(k) ? 1 : 0;
  unsigned long long mine = owned, total = 0;
  MPI_Allreduce(&mine, &total, 1, MPI_UNSIGNED_LONG_LONG, MPI_SUM, MPI_COMM_WORLD);
  std::printf("rank %d: after the start %zu own particles and %zu ghost copies\n", rank_, owned, local.size() - owned);
  check(total == whole, "after the start the ranks own every particle once");
  check(rank_ == 0 || local.size() < whole, "after the start a rank other than 0 holds fewer particles than the whole scene");
  return failures > 0 ? 1 : 0;
}
