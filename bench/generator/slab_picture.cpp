// Writes the data of the docs picture of a filled body (docs/images/filter_cake_slab.png):
//   slab_picture <out_dir> [z_mm = 17.5] [half_thickness_mm = 0.7] [scenes/geometry folder]
// Fills the filter-cake shard (filter_cake_body.hpp, seed 1) and cuts it by the plane z = z_mm:
//   <out_dir>/spheres.dat  x y rho  (mm): the circle where each sphere meets the plane,
//                          rho = sqrt(r^2 - (z_i - z)^2), so the picture shows true sections;
//   <out_dir>/bonds.dat    x y dx dy (mm): bonds whose two centres lie within half_thickness of
//                          the plane, projected on it (a thin slab of the bond network; the
//                          default 0.7 mm is below r_min = 0.71 mm, so each bond end shows a section).
// bench/generator/make_slab_picture.sh runs this and gnuplot (slab_picture.gp).
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include "filter_cake_body.hpp"

#ifndef SHARD_SOURCE_DIR
#define SHARD_SOURCE_DIR "."
#endif

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: slab_picture <out_dir> [z_mm] [half_thickness_mm] [geometry folder]\n");
    return 2;
  }
  const std::filesystem::path out = argv[1];
  const double z = 1e-3 * (argc > 2 ? std::stod(argv[2]) : 17.5);
  const double half = 1e-3 * (argc > 3 ? std::stod(argv[3]) : 0.7);
  shard::GeneratorContext context;
  context.scene_dir = argc > 4 ? argv[4] : SHARD_SOURCE_DIR "/scenes/geometry";
  context.seed = 1;
  context.log = [](const std::string& line) { std::printf("%s\n", line.c_str()); };
  const shard::GeneratedBody body = shard::stl_fill::StlFill(shard::bench::filter_cake_settings()).generate(context);

  std::filesystem::create_directories(out);
  std::ofstream spheres(out / "spheres.dat");
  std::size_t cut = 0;
  for (std::size_t i = 0; i < body.radius.size(); ++i) {
    const double dz = body.position[i].z() - z;
    const double r = body.radius[i];
    if (std::abs(dz) >= r) continue;
    spheres << 1e3 * body.position[i].x() << ' ' << 1e3 * body.position[i].y() << ' '
            << 1e3 * std::sqrt(r * r - dz * dz) << '\n';
    ++cut;
  }
  std::ofstream bonds(out / "bonds.dat");
  std::size_t shown = 0;
  for (const auto& [i, j] : body.bonds) {
    const shard::Vec3& a = body.position[static_cast<std::size_t>(i)];
    const shard::Vec3& b = body.position[static_cast<std::size_t>(j)];
    if (std::abs(a.z() - z) > half || std::abs(b.z() - z) > half) continue;
    bonds << 1e3 * a.x() << ' ' << 1e3 * a.y() << ' ' << 1e3 * (b.x() - a.x()) << ' ' << 1e3 * (b.y() - a.y()) << '\n';
    ++shown;
  }
  std::printf("slab z = %.2f mm: %zu sphere sections, %zu bonds within +-%.2f mm -> %s\n", 1e3 * z, cut, shown,
              1e3 * half, out.string().c_str());
  return spheres && bonds ? 0 : 1;
}
