// Writes beam_bond's reference data (beam_reference.hpp): one TOML file per case into the folder
// given, from the plugin file given. Run after a deliberate physics change only, through
//   cmake --build build/release --target beam_bond_reference
// which writes plugins/bond/beam_bond/reference/ (docs/how-to/write-a-plugin.md, "Reference data").
#include <cstdio>
#include <exception>
#include <string>

#include "beam_reference.hpp"
#include "random_bonds.hpp"
#include "shard/plugin_host.hpp"

namespace {

// 27 pairs (three groups of 8 AVX-512 lanes and a partial one; ends listed both ways, stable ids swapped,
// equal radii) deformed in four growing steps: the first within the fast lanes, the later ones
// past the series range of the rotation and past the strength of a share of the bonds.
constexpr std::size_t kPairs = 27;
constexpr std::uint64_t kSeed = 2026;
constexpr double kScales[] = {1e-4, 3e-3, 1.5e-2, 0.05};
constexpr double kRotationFactor = 4;  // rad per unit of scale: ~0.3 rad by the last step

shard::test::ReferenceData generate(const shard::PluginHost& host, const shard::test::ReferenceCase& c) {
  using namespace shard;
  test::ReferenceData d;
  d.description = c.description;
  d.params = c.params;
  d.dt = 1e-6;
  const auto model = host.make_bond("beam_bond", host.params(PluginKind::Bond, "beam_bond", c.params));
  test::HandBonds s = test::random_pairs<test::HandBonds>(kPairs, kSeed, {true, true});
  s.dt = d.dt;
  d.bonded = s;
  s.initialize(*model);
  for (std::size_t k = 0; k < std::size(kScales); ++k) {
    test::deform(s, 100 + k, kScales[k], kRotationFactor);
    s.compute(*model);
    test::ReferenceStep step;
    step.position = s.position;
    step.orientation = s.orientation;
    step.velocity = s.velocity;
    step.omega = s.omega;
    step.force = s.force;
    step.torque_i = s.torque_i;
    step.torque_j = s.torque_j;
    step.energy = s.energy;
    for (std::size_t b = 0; b < s.i.size(); ++b) {
      step.broken.push_back(s.broken[b]);
      step.sigma_vm.push_back(s.broken[b] ? s.stress[b].sigma_vm : 0.0);
    }
    d.steps.push_back(std::move(step));
  }
  return d;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: %s <shard_beam_bond.so> <output folder>\n", argv[0]);
    return 2;
  }
  try {
    shard::PluginHost host;
    host.load_file(argv[1]);
    for (const auto& c : shard::test::beam_reference_cases()) {
      const std::string path = std::string(argv[2]) + "/" + c.name + ".toml";
      shard::test::write_reference(path, generate(host, c));
      std::printf("wrote %s\n", path.c_str());
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "beam_bond_reference_gen: %s\n", e.what());
    return 1;
  }
  return 0;
}
