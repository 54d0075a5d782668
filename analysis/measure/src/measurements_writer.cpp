#include <fmt/format.h>
#include <fmt/os.h>

#include "shard/measure/measurements.hpp"

namespace shard::measure {
namespace {

// A TOML basic string's content: quotes, backslashes and control characters escaped.
std::string toml_escape(const std::string& text) {
  std::string out;
  for (char ch : text) {
    if (ch == '"' || ch == '\\') out += '\\', out += ch;
    else if (ch == '\n') out += "\\n";
    else if (static_cast<unsigned char>(ch) < 0x20) out += fmt::format("\\u{:04x}", static_cast<unsigned>(ch));
    else out += ch;
  }
  return out;
}

}  // namespace

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
    meta.print("name = \"{}\"\n", toml_escape(set.metadata.name));
    if (!set.metadata.notes.empty()) meta.print("notes = \"{}\"\n", toml_escape(set.metadata.notes));
    meta.print("\n[uncertainty]\nload_cell = {:.6g}      # N, standard uncertainty of a force reading\n"
               "displacement = {:.6g}   # m, standard uncertainty of a displacement reading\n",
               set.metadata.load_cell_uncertainty, set.metadata.displacement_uncertainty);
    if (set.metadata.crack_position_uncertainty > 0)
      meta.print("crack_position = {:.6g} # m\n", set.metadata.crack_position_uncertainty);
    const TestConditions& t = set.metadata.test;
    std::string test;
    if (t.seating_preload > 0)
      test += fmt::format("seating_preload = {:.9g}   # N: each curve starts (t = 0, d = 0) where the force reached it\n",
                          t.seating_preload);
    if (t.zero_offset != 0)
      test += fmt::format("zero_offset = {:.9g}   # N: the load cell's reading at zero load, subtracted when read\n",
                          t.zero_offset);
    if (!t.ramp.empty()) test += fmt::format("ramp = \"{}\"\n", t.ramp);
    if (t.ramp_time > 0) test += fmt::format("ramp_time = {:.9g}   # s, of the pins to reach the loading rate\n", t.ramp_time);
    if (t.grain_size > 0) test += fmt::format("grain_size = {:.9g}   # m\n", t.grain_size);
    if (t.fragment_size_threshold > 0)
      test += fmt::format("fragment_size_threshold = {:.9g}   # m: smaller fragments were not counted\n",
                          t.fragment_size_threshold);
    if (!t.notes.empty()) test += fmt::format("notes = \"{}\"\n", toml_escape(t.notes));
    if (!test.empty()) meta.print("\n[test]\n{}", test);
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
