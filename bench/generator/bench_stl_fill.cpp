// Benchmark of the stl_fill generator on the scenes' bodies (one core):
//   bench_stl_fill [shard|beam|all] [scenes/geometry folder] [d_min_mm d_max_mm]
// Prints the quality figures, the generation time (wall, from the generator's log) and the
// process CPU time (the honest figure on a shared, loaded machine). Speed targets: <= 5 s for
// the ~4e4-sphere filter-cake shard, <= 60 s for the ~3e5-sphere calibration beam. A last line
// scans the bond gap to show which value gives coordination ~11. The optional diameters replace
// the body's default range (used to choose the shard's range that gives ~4e4 spheres).
#include <cstdio>
#include <ctime>
#include <string>

#include "shard/geometry/packing_quality.hpp"
#include "filter_cake_body.hpp"
#include "stl_fill.hpp"

#ifndef SHARD_SOURCE_DIR
#define SHARD_SOURCE_DIR "."
#endif

namespace {

constexpr double kBeamDMin = 0.7e-3, kBeamDMax = 1.0e-3;

double cpu_seconds() { return static_cast<double>(std::clock()) / CLOCKS_PER_SEC; }

void run(const std::string& folder, const std::string& file, double d_min, double d_max) {
  shard::stl_fill::StlFillSettings s;
  s.file = file;
  s.scale = 0.001;
  s.diameter_min = d_min;
  s.diameter_max = d_max;
  shard::GeneratorContext context;
  context.scene_dir = folder;
  context.seed = 1;
  context.log = [](const std::string& line) { std::printf("%s\n", line.c_str()); };
  const double cpu_start = cpu_seconds();
  const shard::GeneratedBody body = shard::stl_fill::StlFill(s).generate(context);
  std::printf("%s d=%.3g..%.3g mm: generation CPU time %.2f s\n", file.c_str(), 1e3 * d_min, 1e3 * d_max,
              cpu_seconds() - cpu_start);
  shard::geometry::SpherePacking packing{body.position, body.radius};
  std::printf("%s d=%.3g..%.3g mm: coordination versus gap:", file.c_str(), 1e3 * d_min, 1e3 * d_max);
  for (double gap : {0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8}) {
    const auto bonds = shard::geometry::bond_by_gap(packing, gap);
    std::printf(" %.2f:%.2f", gap, 2.0 * static_cast<double>(bonds.size()) / static_cast<double>(body.radius.size()));
  }
  std::printf("\n");
}

}  // namespace

int main(int argc, char** argv) {
  const std::string which = argc > 1 ? argv[1] : "all";
  const std::string folder = argc > 2 ? argv[2] : SHARD_SOURCE_DIR "/scenes/geometry";
  const bool custom = argc > 4;
  const double d_min = custom ? 1e-3 * std::stod(argv[3]) : 0.0;
  const double d_max = custom ? 1e-3 * std::stod(argv[4]) : 0.0;
  if (which == "shard" || which == "all")
    run(folder, "filter_cake_shard.stl", custom ? d_min : shard::bench::kShardDMin,
        custom ? d_max : shard::bench::kShardDMax);
  if (which == "beam" || which == "all")
    run(folder, "beam_180x30x35.stl", custom ? d_min : kBeamDMin, custom ? d_max : kBeamDMax);
  return 0;
}
