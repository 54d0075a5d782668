// Benchmark of the stl_fill generator on the scenes' bodies (one core):
//   bench_stl_fill [shard|beam|all] [scenes/geometry folder]
// Prints the quality figures and the generation time; speed targets: <= 5 s for the ~4e4-sphere
// filter-cake shard, <= 60 s for the ~3e5-sphere calibration beam. A third column scans the bond
// gap to show which value gives coordination ~11.
#include <cstdio>
#include <string>

#include "shard/geometry/packing_quality.hpp"
#include "stl_fill.hpp"

#ifndef SHARD_SOURCE_DIR
#define SHARD_SOURCE_DIR "."
#endif

namespace {

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
  const shard::GeneratedBody body = shard::stl_fill::StlFill(s).generate(context);
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
  if (which == "shard" || which == "all") run(folder, "filter_cake_shard.stl", 1.5e-3, 2.0e-3);
  if (which == "beam" || which == "all") run(folder, "beam_180x30x35.stl", 0.7e-3, 1.0e-3);
  return 0;
}
