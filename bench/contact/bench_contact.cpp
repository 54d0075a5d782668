// The contact law alone, without the neighbour search and integration around it (docs/explanation/performance.md):
//   bench_contact PLUGIN [contacts=4096] [steps=2000] [key=value ...] [materials=M]
// e.g. bench_contact hertz_mindlin 4096 2000 effects=cohesion cohesion_stress=5e4
// A fixed random batch (a quarter particle-wall contacts, overlaps 1e-4..1e-2 of the radius,
// relative speeds up to 0.1 m/s, so some contacts slide) is computed `steps` times through the
// plugin's compute(), the tangential springs carrying over as in a run. Prints the CPU ns per
// contact-step and a hash of the final forces, springs and energies (equal hash: same bits).
#include <time.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <random>
#include <stdexcept>
#include <string>
#include <variant>
#include <vector>

#include "shard/plugin_host.hpp"

using namespace shard;

namespace {

double cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

std::uint64_t fnv1a(std::uint64_t h, const double* v, std::size_t n) {
  for (std::size_t c = 0; c < n; ++c) {
    std::uint64_t bits;
    std::memcpy(&bits, v + c, sizeof bits);
    for (int b = 0; b < 8; ++b) {
      h ^= (bits >> (8 * b)) & 0xffu;
      h *= 1099511628211ull;
    }
  }
  return h;
}

// "key=value": a number unless it does not parse as one, then text (e.g. effects=cohesion).
std::map<std::string, ParamValue> overrides(int argc, char** argv, int first) {
  std::map<std::string, ParamValue> out;
  for (int a = first; a < argc; ++a) {
    const std::string s = argv[a];
    const auto eq = s.find('=');
    if (eq == std::string::npos) throw std::invalid_argument("expected key=value, got '" + s + "'");
    const std::string value = s.substr(eq + 1);
    char* end = nullptr;
    const double number = std::strtod(value.c_str(), &end);
    if (end != value.c_str() && *end == '\0')
      out[s.substr(0, eq)] = number;
    else
      out[s.substr(0, eq)] = value;
  }
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: bench_contact PLUGIN [contacts=4096] [steps=2000] [key=value ...]\n");
    return 2;
  }
  try {
    const std::string plugin = argv[1];
    const std::size_t n = argc > 2 ? static_cast<std::size_t>(std::atof(argv[2])) : 4096;
    const long steps = argc > 3 ? std::atol(argv[3]) : 2000;
    PluginHost host;
    host.load_directories(PluginHost::default_search_path());
    // materials=M (docs/reference/materials.md): a table of M materials, all of the plugin's values, and each
    // contact of a random pair: the cost of gathering the pair's row per lane (M = 1: no table).
    auto values = overrides(argc, argv, 4);
    std::size_t materials = 1;
    if (const auto it = values.find("materials"); it != values.end()) {
      materials = static_cast<std::size_t>(std::get<double>(it->second));
      values.erase(it);
    }
    const ParamSet params = host.params(PluginKind::Contact, plugin, values);
    const auto model = host.make_contact(plugin, params);
    std::vector<std::int32_t> rows;
    if (materials > 1) {
      ContactMaterials table;
      table.count = materials;
      for (std::size_t m = 0; m < materials; ++m) table.names.push_back(std::to_string(m)), table.material.push_back(params);
      table.pair.assign(materials * materials, params);
      model->set_materials(table);
      std::mt19937 pick(7);
      for (std::size_t k = 0; k < n; ++k) rows.push_back(static_cast<std::int32_t>(pick() % (materials * materials)));
    }

    std::mt19937_64 rng(20261202);
    std::uniform_real_distribution<double> u(-1.0, 1.0), unit(0.0, 1.0);
    const double radius = 5e-4, mass = 2500 * 4.18879 * radius * radius * radius;
    std::vector<Index> i(n), j(n);
    std::vector<Vec3> normal(n), velocity(n), omega(n, Vec3::Zero()), force(n), couple(n);
    std::vector<double> overlap(n), r_eff(n), m_eff(n), energy(n);
    std::vector<double> history(n * model->history_size(), 0.0);
    for (std::size_t k = 0; k < n; ++k) {
      const bool wall = k % 4 == 3;
      i[k] = static_cast<Index>(k);
      j[k] = wall ? -1 : static_cast<Index>(k + 1);
      Vec3 d(u(rng), u(rng), u(rng));
      normal[k] = d.normalized();
      velocity[k] = 0.1 * Vec3(u(rng), u(rng), u(rng));
      overlap[k] = radius * std::pow(10.0, -4.0 + 2.0 * unit(rng));
      r_eff[k] = wall ? radius : 0.5 * radius;
      m_eff[k] = wall ? mass : 0.5 * mass;
    }
    ContactBatch batch;
    batch.count = n;
    batch.dt = 1e-6;
    batch.i = i.data(), batch.j = j.data(), batch.normal = normal.data(), batch.overlap = overlap.data();
    batch.velocity = velocity.data(), batch.omega_rel = omega.data(), batch.r_eff = r_eff.data();
    batch.m_eff = m_eff.data(), batch.history = history.data(), batch.force = force.data();
    batch.couple = couple.data(), batch.energy = energy.data();
    batch.material_pair = rows.empty() ? nullptr : rows.data();

    const double cpu0 = cpu_seconds();
    for (long s = 0; s < steps; ++s) {
      for (std::size_t k = 0; k < n; ++k) force[k].setZero(), couple[k].setZero(), energy[k] = 0;
      model->compute(batch);
    }
    const double cpu = cpu_seconds() - cpu0;
    std::uint64_t h = 1469598103934665603ull;
    h = fnv1a(h, force.front().data(), 3 * n);
    h = fnv1a(h, history.data(), history.size());
    h = fnv1a(h, energy.data(), n);
    std::printf("bench_contact %s: contacts=%zu steps=%ld materials=%zu cpu_seconds=%.3f cpu_ns_per_contact_step=%.2f "
                "hash=%016llx\n",
                plugin.c_str(), n, steps, materials, cpu, 1e9 * cpu / (static_cast<double>(n) * static_cast<double>(steps)),
                static_cast<unsigned long long>(h));
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_contact: %s\n", e.what());
    return 1;
  }
  return 0;
}
