// The contact laws against their stored reference results (contact_reference.hpp), through the
// plugin interface: the shipped plugin files, the stored inputs, the stored forces, couples,
// energies and tangential springs over four steps.
//
// Tolerance: |now - stored| <= 1e-11 |stored| + 1e-15 max|stored| of the quantity (force, couple,
// energy, spring). The laws are IEEE arithmetic without fused multiply-adds, so on x86-64 the
// results repeat bit for bit (the test reports how many do). The relative term lets another
// compiler or a reordered but equivalent expression pass (a few ulp, 1e-15, on each operation) and
// still fails a physics change of 1e-9 in any value above a millionth of its quantity's largest;
// the absolute floor, ~5 ulp of the largest value, covers components that cancel to near zero. After a deliberate change: regenerate
// (plugins/contact/README.md) and say why in the commit.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstring>

#include "contact_reference.hpp"

using namespace shard;
using namespace shard::test;

TEST_CASE("each contact law and policy reproduces its stored reference results") {
  PluginHost host;
  host.load_directories({SHARD_BUILD_DIR "/plugins"});
  for (const auto& c : reference_cases()) {
    CAPTURE(c.file);
    const StoredReference stored = read_reference(reference_file(SHARD_SOURCE_DIR, c));
    // A file of another case or parameter set is stale: regenerate it.
    REQUIRE(stored.c.plugin == c.plugin);
    REQUIRE(stored.c.params == c.params);
    REQUIRE(stored.run.count >= 32);
    const ReferenceRun now = run_case(host, c, stored.run.inputs, stored.run.dt, stored.run.steps);

    // Quantity groups: force (0-2), couple (3-5), energy (6), spring (7-9).
    const int group_of[10] = {0, 0, 0, 1, 1, 1, 2, 3, 3, 3};
    double scale[4] = {0, 0, 0, 0};
    for (const auto& step : stored.run.results)
      for (const auto& r : step)
        for (int q = 0; q < 10; ++q) scale[group_of[q]] = std::max(scale[group_of[q]], std::abs(r[q]));
    CHECK(scale[0] > 0);
    CHECK(scale[2] > 0);
    std::size_t beyond = 0, same_bits = 0, values = 0, sliding = 0, sticking = 0, clamped = 0;
    for (int s = 0; s < stored.run.steps; ++s)
      for (std::size_t k = 0; k < stored.run.count; ++k) {
        const auto& want = stored.run.results[static_cast<std::size_t>(s)][k];
        const auto& got = now.results[static_cast<std::size_t>(s)][k];
        for (int q = 0; q < 10; ++q, ++values) {
          same_bits += std::memcmp(&want[q], &got[q], sizeof(double)) == 0 ? 1 : 0;
          if (!(std::abs(want[q] - got[q]) <= 1e-11 * std::abs(want[q]) + 1e-15 * scale[group_of[q]])) {
            ++beyond;
            if (beyond <= 5) MESSAGE("step ", s, " contact ", k, " column ", q, ": stored ", number(want[q]), ", now ", number(got[q]));
          }
        }
        // The regimes the law selects between, seen in the stored forces (mu = 0.67, the default).
        const Vec3 n = stored.run.inputs.normal[k], f(want[0], want[1], want[2]);
        const double f_n = f.dot(n), f_t = (f - f_n * n).norm();
        if (f.norm() == 0) ++clamped;
        else if (std::abs(f_t - 0.67 * f_n) <= 1e-9 * f_t) ++sliding;
        else if (f_t < 0.67 * f_n) ++sticking;
      }
    MESSAGE(c.file, ": ", same_bits, " of ", values, " values bit-identical to the stored ones");
    CHECK(beyond == 0);
    if (c.params.empty()) {
      MESSAGE("sliding ", sliding, ", sticking ", sticking, ", clamped ", clamped, " of ", stored.run.steps * stored.run.count);
      CHECK(sliding >= 10);
      CHECK(sticking >= 10);
      CHECK(clamped >= 3);
    }
  }
}
