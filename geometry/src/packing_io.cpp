#include "shard/geometry/packing_io.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <stdexcept>

#include "shard/io/csv.hpp"

namespace shard::geometry {
namespace {

// Read by the one CSV reader (shard/io/csv.hpp): an optional header, ',' or ';' or tab, decimal
// commas; rows of one length, errors with file:line:column.
io::CsvTable read_table(const std::filesystem::path& file, const char* what) {
  if (!std::filesystem::is_regular_file(file))
    throw std::runtime_error(fmt::format("{} file '{}' cannot be opened: check the path (relative paths are "
                                         "resolved against the scene folder)",
                                         what, file.string()));
  return io::CsvTable::read(file, io::CsvHeader::optional);
}

}  // namespace

std::filesystem::path bonds_path_for(const std::filesystem::path& spheres_file) {
  std::filesystem::path p = spheres_file;
  return p.replace_extension(".bonds.csv");
}

void save_packing_csv(const std::filesystem::path& spheres_file, const SpherePacking& packing, const BondList& bonds,
                      const std::vector<std::string>& comment) {
  if (spheres_file.has_parent_path()) std::filesystem::create_directories(spheres_file.parent_path());
  std::ofstream spheres(spheres_file);
  if (!spheres) throw std::runtime_error(fmt::format("cannot write packing file '{}'", spheres_file.string()));
  for (const auto& line : comment) spheres << "# " << line << '\n';
  spheres << "x,y,z,r,material\n";
  for (std::size_t i = 0; i < packing.centre.size(); ++i) {
    const Vec3& c = packing.centre[i];
    spheres << fmt::format("{:.17g},{:.17g},{:.17g},{:.17g},0\n", c.x(), c.y(), c.z(), packing.radius[i]);
  }
  std::ofstream bond_file(bonds_path_for(spheres_file));
  if (!bond_file) throw std::runtime_error(fmt::format("cannot write bonds file '{}'", bonds_path_for(spheres_file).string()));
  bond_file << "i,j\n";
  for (const auto& [i, j] : bonds) bond_file << i << ',' << j << '\n';
  if (!spheres || !bond_file) throw std::runtime_error(fmt::format("writing packing '{}' failed (disk full?)", spheres_file.string()));
}

StoredPacking read_spheres_csv(const std::filesystem::path& file) {
  const auto t = read_table(file, "spheres");
  StoredPacking stored;
  const bool with_material = !t.rows().empty() && t.rows()[0].fields.size() >= 5;
  for (const auto& row : t.rows()) {
    if (row.fields.size() != (with_material ? 5u : 4u))
      t.fail(row, 0, fmt::format("spheres file: {} columns", row.fields.size()), "expected x,y,z,r[,material] in m");
    double v[5] = {0, 0, 0, 0, 0};
    for (std::size_t c = 0; c < row.fields.size(); ++c) v[c] = t.number(row, c, "x,y,z,r[,material] in m");
    if (!(v[3] > 0.0)) t.fail(row, 3, "spheres file: values must be finite and the radius > 0", "write the radius in m");
    stored.spheres.centre.emplace_back(v[0], v[1], v[2]);
    stored.spheres.radius.push_back(v[3]);
    if (with_material) {
      if (v[4] < 0.0 || v[4] != std::floor(v[4]))
        t.fail(row, 4, "spheres file: material must be an integer >= 0", "write the material index 0, 1, ...");
      stored.material.push_back(static_cast<std::int32_t>(v[4]));
    }
  }
  if (stored.spheres.centre.empty())
    throw std::runtime_error(fmt::format("spheres file '{}' has no spheres: expected lines x,y,z,r[,material] in m",
                                         file.string()));
  return stored;
}

BondList read_bonds_csv(const std::filesystem::path& file, std::size_t particles) {
  const auto t = read_table(file, "bonds");
  BondList bonds;
  const auto n = static_cast<double>(particles);
  const std::string fix = fmt::format("expected two different sphere indices i,j in [0, {}) (0-based rows of the "
                                      "spheres file)",
                                      particles);
  for (const auto& row : t.rows()) {
    if (row.fields.size() != 2) t.fail(row, 0, fmt::format("bonds file: {} columns", row.fields.size()), fix);
    const double i = t.number(row, 0, "index i"), j = t.number(row, 1, "index j");
    if (!(i >= 0 && i < n && j >= 0 && j < n) || i != std::floor(i) || j != std::floor(j) || i == j)
      t.fail(row, 0, "bonds file: not a bond", fix);
    bonds.emplace_back(std::min(static_cast<Index>(i), static_cast<Index>(j)),
                       std::max(static_cast<Index>(i), static_cast<Index>(j)));
  }
  std::vector<std::pair<Index, Index>> sorted = bonds;
  std::sort(sorted.begin(), sorted.end());
  if (const auto dup = std::adjacent_find(sorted.begin(), sorted.end()); dup != sorted.end())
    throw std::runtime_error(fmt::format("bonds file '{}': the pair {},{} appears twice; remove the duplicate",
                                         file.string(), dup->first, dup->second));
  return bonds;
}

}  // namespace shard::geometry

namespace shard::geometry {

std::filesystem::path resolve_against(const std::string& scene_dir, const std::string& file) {
  const std::filesystem::path path(file);
  if (path.is_absolute() || scene_dir.empty()) return path;
  return std::filesystem::path(scene_dir) / path;
}

GeneratedBody to_generated_body(SpherePacking packing, BondList bonds, std::vector<std::int32_t> material,
                                std::vector<std::pair<std::string, double>> quality) {
  GeneratedBody body;
  body.position = std::move(packing.centre);
  body.radius = std::move(packing.radius);
  body.material = std::move(material);
  body.bonds = std::move(bonds);
  body.quality = std::move(quality);
  return body;
}

}  // namespace shard::geometry
