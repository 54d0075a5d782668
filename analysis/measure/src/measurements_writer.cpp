#include <fmt/format.h>
#include <fmt/os.h>

#include "shard/measure/measurements.hpp"

namespace shard::measure {

void write_curve(const std::filesystem::path& file, const Curve& c) {
  auto out = fmt::output_file(file.string());
  out.print("time,displacement,force,u_displacement,u_force\n");
  for (std::size_t k = 0; k < c.size(); ++k)
    out.print("{:.9g},{:.9g},{:.9g},{:.6g},{:.6g}\n", c.time[k], c.displacement[k], c.force[k], c.u_displacement[k],
              c.u_force[k]);
}

void write_measurements(const MeasurementSet& set, const std::filesystem::path& folder) {
  std::filesystem::create_directories(folder / "curves");
  {
    auto meta = fmt::output_file((folder / "metadata.toml").string());
    meta.print("name = \"{}\"\n\n[uncertainty]\nload_cell = {:.6g}      # N, standard uncertainty of a force reading\n"
               "displacement = {:.6g}   # m, standard uncertainty of a displacement reading\n",
               set.metadata.name, set.metadata.load_cell_uncertainty, set.metadata.displacement_uncertainty);
    if (set.metadata.crack_position_uncertainty > 0)
      meta.print("crack_position = {:.6g} # m\n", set.metadata.crack_position_uncertainty);
  }
  bool any_fragments = false;
  for (const auto& s : set.specimens) any_fragments = any_fragments || !s.fragment_sizes.empty();
  if (any_fragments) std::filesystem::create_directories(folder / "fragments");
  auto table = fmt::output_file((folder / "specimens.csv").string());
  table.print("id,length,width,height,span,pin_distance,loading_rate,crack_position,fragment_count\n");
  for (const auto& s : set.specimens) {
    table.print("{},{:.6g},{:.6g},{:.6g},{:.6g},{:.6g},{:.6g},{},{}\n", s.id, s.length, s.width, s.height, s.span,
                s.pin_distance, s.loading_rate, s.crack_position ? fmt::format("{:.6g}", *s.crack_position) : "",
                s.fragment_count ? fmt::format("{:.0f}", *s.fragment_count) : "");
    write_curve(folder / "curves" / (s.id + ".csv"), s.curve);
    if (!s.fragment_sizes.empty()) {
      auto f = fmt::output_file((folder / "fragments" / (s.id + ".csv")).string());
      f.print("size\n");
      for (double x : s.fragment_sizes) f.print("{:.6g}\n", x);
    }
  }
}

}  // namespace shard::measure
