// Step-loop benchmarks (docs/explanation/performance.md). One summary line per benchmark, so a
// later change can be compared line by line:
//   bench_kernel bonded  [particles=20000] [pull_speed=0.2] [max_steps=20000]
//   bench_kernel bonded_effects [same] [policies=all]  (the bond's effect policies on at the
//       effect library's plausible sizes, docs/reference/effects.md; policies: a comma list of
//       weibull_strength, softening, viscosity, compression_asymmetry; any other name is named in
//       `effects` at its neutral values, e.g. an out-of-tree bond effect found on SHARD_PLUGIN_PATH)
//   bench_kernel settle  [particles=100000] [steps=1000]
//   bench_kernel scaling [steps=200]   (dense pack at 1e4, 1e5, 3e5 spheres)
//   bench_kernel scene FILE [steps=200] [block=0]  (a scene file's Simulation as `shard run` builds
//       it; only the step calls are timed, after a set-up line a profiler can wait for; block > 0:
//       the bonded bench block of that many spheres stepped in turn with it, and the ratio)
// Threads come from OMP_NUM_THREADS; pin with taskset for stable figures.
#include <omp.h>

#include <time.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <map>
#include <memory>
#include <utility>
#include <stdexcept>
#include <string>
#include <vector>

#include "bench_scenes.hpp"
#include "shard/scene.hpp"

using namespace shard;
using Clock = std::chrono::steady_clock;

namespace {

double arg(int argc, char** argv, int k, double fallback) { return argc > k ? std::atof(argv[k]) : fallback; }

double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

// CPU seconds of all the process's threads: on a shared machine the wall time also counts the
// time other processes held the cores, the CPU time does not.
double cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

// FNV-1a (bonded and pack lines) over the bits of every particle's position, orientation, velocity and spin, taken
// in stable-id order: equal hashes mean a bit-identical state whatever the internal numbering, so
// a speed-up can be checked not to have moved a single bit (docs/explanation/performance.md).
std::uint64_t state_hash(const Particles& p) {
  std::vector<std::size_t> by_id(p.size());
  for (std::size_t k = 0; k < p.size(); ++k) by_id[static_cast<std::size_t>(p.id[k])] = k;
  std::uint64_t h = 1469598103934665603ull;
  const auto mix = [&h](const double* v, std::size_t n) {
    for (std::size_t c = 0; c < n; ++c) {
      std::uint64_t bits;
      std::memcpy(&bits, v + c, sizeof bits);
      for (int b = 0; b < 8; ++b) {
        h ^= (bits >> (8 * b)) & 0xffu;
        h *= 1099511628211ull;
      }
    }
  };
  for (const std::size_t k : by_id) {
    mix(p.position[k].data(), 3);
    mix(p.orientation[k].coeffs().data(), 4);
    mix(p.velocity[k].data(), 3);
    mix(p.omega[k].data(), 3);
  }
  return h;
}

// Tension of the block: the x force the bonds pull the +x slab back with.
double slab_force(const Simulation& sim) {
  const Particles& p = sim.particles();
  double f = 0;
  for (std::size_t k = 0; k < p.size(); ++k)
    if ((p.flags[k] & kPrescribed) && p.velocity[k].x() > 0) f -= p.force[k].x();
  return f;
}

// The plausible sizes of scenes/measurements/effects.toml: m 4, s 1, tau_v 1e-3 s, r 2.
std::map<std::string, ParamValue> bond_effects(const std::string& policies) {
  const std::map<std::string, std::pair<std::string, double>> size{
      {"weibull_strength", {"strength_weibull_modulus", 4.0}},
      {"softening", {"softening_ratio", 1.0}},
      {"viscosity", {"viscosity_time", 1e-3}},
      {"compression_asymmetry", {"compression_stiffness_ratio", 2.0}}};
  std::map<std::string, ParamValue> out;
  for (const auto& [name, param] : size)
    if (policies == "all" || ("," + policies + ",").find("," + name + ",") != std::string::npos)
      out[param.first] = param.second;
  std::string named;  // names of no size above: named in `effects`, e.g. an out-of-tree bond effect
  for (std::size_t at = 0; policies != "all" && at <= policies.size();) {
    const std::size_t end = std::min(policies.find(',', at), policies.size());
    const std::string name = policies.substr(at, end - at);
    if (!name.empty() && !size.count(name)) named += (named.empty() ? "" : ",") + name;
    at = end + 1;
  }
  if (!named.empty()) out["effects"] = named;
  if (out.empty()) throw std::invalid_argument("bonded_effects: no policy in '" + policies + "'");
  return out;
}

void bonded(int argc, char** argv, const char* name, const std::map<std::string, ParamValue>& bond_params) {
  const auto target = static_cast<std::size_t>(arg(argc, argv, 2, 20000));
  const double speed = arg(argc, argv, 3, 0.2);
  const auto max_steps = static_cast<std::int64_t>(arg(argc, argv, 4, 20000));
  const bench::Models models = bench::default_models(bond_params);
  Simulation sim(bench::bonded_block(target, speed, models));
  const std::size_t bonds0 = sim.bonds().size();
  double bond_steps = 0, peak = 0, force = 0;
  std::int64_t steps = 0;
  double busy = 0, cpu = 0;
  // Until the block has parted: tension below 5 % of its peak after bonds started to break.
  while (steps < max_steps) {
    const auto t0 = Clock::now();
    const double c0 = cpu_seconds();
    for (int s = 0; s < 100; ++s) {
      bond_steps += static_cast<double>(sim.bonds().size());
      sim.step();
    }
    busy += seconds_since(t0);
    cpu += cpu_seconds() - c0;
    steps += 100;
    force = slab_force(sim);
    peak = std::max(peak, force);
    if (sim.bonds_broken() > 0 && force < 0.05 * peak) break;
  }
  std::printf(
      "bench_kernel %s: particles=%zu bonds=%zu threads=%d steps=%lld dt=%.3e contacts=%zu broken=%lld peak_force_N=%.4g "
      "rebuilds=%lld seconds=%.3f cpu_seconds=%.3f bond_steps_per_s=%.4g ns_per_bond_step=%.2f cpu_ns_per_bond_step=%.2f "
      "parted=%s state_hash=%016llx\n",
      name, sim.particles().size(), bonds0, omp_get_max_threads(), static_cast<long long>(steps), sim.dt(),
      sim.contact_count(), static_cast<long long>(sim.bonds_broken()), peak, static_cast<long long>(sim.neighbour_rebuilds()), busy,
      cpu, bond_steps / busy, 1e9 * busy / bond_steps, 1e9 * cpu / bond_steps, steps < max_steps ? "yes" : "no",
      static_cast<unsigned long long>(state_hash(sim.particles())));
}

void pack_run(const char* name, std::size_t target, std::int64_t steps) {
  const bench::Models models = bench::default_models();
  Simulation sim(bench::dense_pack(target, models));
  const auto t0 = Clock::now();
  const double c0 = cpu_seconds();
  sim.run(steps);
  const double busy = seconds_since(t0);
  const double cpu = cpu_seconds() - c0;
  const double n = static_cast<double>(sim.particles().size());
  std::printf(
      "bench_kernel %s: particles=%zu threads=%d steps=%lld dt=%.3e contacts=%zu rebuilds=%lld seconds=%.3f "
      "cpu_seconds=%.3f ms_per_step=%.3f particle_steps_per_s=%.4g ns_per_particle_step=%.1f cpu_ns_per_particle_step=%.1f "
      "state_hash=%016llx\n",
      name, sim.particles().size(), omp_get_max_threads(), static_cast<long long>(steps), sim.dt(),
      sim.contact_count(), static_cast<long long>(sim.neighbour_rebuilds()), busy, cpu, 1e3 * busy / static_cast<double>(steps),
      n * static_cast<double>(steps) / busy, 1e9 * busy / (n * static_cast<double>(steps)),
      1e9 * cpu / (n * static_cast<double>(steps)), static_cast<unsigned long long>(state_hash(sim.particles())));
}

// Step calls timed on one Simulation, in slices: a run of several Simulations stepped in turn
// shares whatever load the machine has at each moment between them.
struct TimedRun {
  Simulation* sim;
  std::size_t bonds0;
  double bond_steps = 0, seconds = 0, cpu = 0;
  std::int64_t steps = 0;

  explicit TimedRun(Simulation& s) : sim(&s), bonds0(s.bonds().size()) {}
  void advance(std::int64_t count) {
    const auto t0 = Clock::now();
    const double c0 = cpu_seconds();
    for (std::int64_t k = 0; k < count; ++k) {
      bond_steps += static_cast<double>(sim->bonds().size());
      sim->step();
    }
    seconds += seconds_since(t0);
    cpu += cpu_seconds() - c0;
    steps += count;
  }
  void print(const char* what) const {
    const Simulation& s = *sim;
    std::printf(
        "bench_kernel scene: %s particles=%zu bonds=%zu threads=%d steps=%lld dt=%.3e contacts=%zu broken=%lld "
        "rebuilds=%lld seconds=%.3f cpu_seconds=%.3f ms_per_step=%.3f ns_per_bond_step=%.2f cpu_ns_per_bond_step=%.2f "
        "state_hash=%016llx\n",
        what, s.particles().size(), bonds0, omp_get_max_threads(), static_cast<long long>(steps), s.dt(),
        s.contact_count(), static_cast<long long>(s.bonds_broken()), static_cast<long long>(s.neighbour_rebuilds()),
        seconds, cpu, 1e3 * seconds / static_cast<double>(steps), 1e9 * seconds / bond_steps, 1e9 * cpu / bond_steps,
        static_cast<unsigned long long>(state_hash(s.particles())));
  }
};

// A scene file's whole Simulation (generation included) stepped `steps` times. The set-up line goes
// out before the first step, so a profiler started on it sees the step loop alone. With `block` > 0
// the bonded bench block of that many spheres is stepped in turn with it, 5 timed steps each, and the
// ratio of their CPU time per bond-step printed: on a shared machine the two figures taken apart
// move with the load, their ratio taken this way much less.
void scene_run(const char* file, std::int64_t steps, std::size_t block) {
  const Scene scene = load_scene(file, std::vector<std::string>{}, bench::host());
  const auto s0 = Clock::now();
  SceneInstance inst = instantiate(scene, bench::host(), [](const std::string&) {});
  const bench::Models models = bench::default_models();
  std::unique_ptr<Simulation> bench_block;
  if (block > 0) bench_block = std::make_unique<Simulation>(bench::bonded_block(block, 0.2, models));
  std::printf("bench_kernel scene: set-up %.1f s, stepping\n", seconds_since(s0));
  std::fflush(stdout);
  TimedRun run(*inst.simulation);
  if (!bench_block) {
    run.advance(steps);
  } else {
    TimedRun other(*bench_block);
    for (std::int64_t k = 0; k < steps; k += 5) {
      // Each slice starts with an untimed step that brings its arrays back into the caches the
      // other Simulation's slice evicted: the block alone runs from warm caches.
      inst.simulation->step();
      run.advance(std::min<std::int64_t>(5, steps - k));
      bench_block->step();
      other.advance(std::min<std::int64_t>(5, steps - k));
    }
    other.print("bench_block");
    std::printf("bench_kernel scene: cpu_per_bond_step_ratio=%.3f (scene over bench block, stepped in turn)\n",
                (run.cpu / run.bond_steps) / (other.cpu / other.bond_steps));
  }
  run.print((std::string("file=") + file).c_str());
}

}  // namespace

int main(int argc, char** argv) {
  const std::string which = argc > 1 ? argv[1] : "";
  try {
    if (which == "bonded") {
      bonded(argc, argv, "bonded", {});
    } else if (which == "bonded_effects") {
      bonded(argc, argv, "bonded_effects", bond_effects(argc > 5 ? argv[5] : "all"));
    } else if (which == "settle") {
      pack_run("settle", static_cast<std::size_t>(arg(argc, argv, 2, 1e5)), static_cast<std::int64_t>(arg(argc, argv, 3, 1000)));
    } else if (which == "scaling") {
      const auto steps = static_cast<std::int64_t>(arg(argc, argv, 2, 200));
      for (double n : {1e4, 1e5, 3e5}) pack_run("scaling", static_cast<std::size_t>(n), steps);
    } else if (which == "scene" && argc > 2) {
      scene_run(argv[2], static_cast<std::int64_t>(arg(argc, argv, 3, 200)), static_cast<std::size_t>(arg(argc, argv, 4, 0)));
    } else {
      std::fprintf(stderr, "usage: bench_kernel bonded|bonded_effects|settle|scaling|scene [args]  (see the file header)\n");
      return 2;
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_kernel: %s\n", e.what());
    return 1;
  }
  return 0;
}
