#include "shard/geometry/packing_io.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace shard::geometry {
namespace {

std::ifstream open_or_throw(const std::filesystem::path& file, const char* what) {
  std::ifstream in(file);
  if (!in)
    throw std::runtime_error(fmt::format("{} file '{}' cannot be opened: check the path (relative paths are "
                                         "resolved against the scene folder)",
                                         what, file.string()));
  return in;
}

// Splits a CSV data line into numbers; false for comments, blank lines and a header.
bool parse_numbers(std::string line, std::vector<double>& values) {
  values.clear();
  const auto first = line.find_first_not_of(" \t\r");
  if (first == std::string::npos || line[first] == '#') return false;
  std::replace(line.begin(), line.end(), ',', ' ');
  std::istringstream in(line);
  std::string field;
  while (in >> field) {
    char* end = nullptr;
    const double v = std::strtod(field.c_str(), &end);
    if (end == field.c_str() || *end != '\0') {
      values.clear();
      values.push_back(std::numeric_limits<double>::quiet_NaN());  // marks a text field
      return true;
    }
    values.push_back(v);
  }
  return !values.empty();
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
  std::ifstream in = open_or_throw(file, "spheres");
  StoredPacking stored;
  std::string line;
  std::vector<double> v;
  std::size_t row = 0;
  bool with_material = false;
  while (std::getline(in, line)) {
    ++row;
    if (!parse_numbers(line, v)) continue;
    if (std::isnan(v[0])) {
      if (stored.spheres.centre.empty()) continue;  // header
      throw std::runtime_error(fmt::format("spheres file '{}' line {}: a non-numeric field; expected x,y,z,r[,material]",
                                           file.string(), row));
    }
    if (stored.spheres.centre.empty()) with_material = v.size() >= 5;
    if (v.size() != (with_material ? 5u : 4u))
      throw std::runtime_error(fmt::format("spheres file '{}' line {}: {} columns, expected {} (x,y,z,r{}) as on the "
                                           "first data line",
                                           file.string(), row, v.size(), with_material ? 5 : 4,
                                           with_material ? ",material" : ""));
    if (!std::all_of(v.begin(), v.end(), [](double x) { return std::isfinite(x); }) || !(v[3] > 0.0))
      throw std::runtime_error(fmt::format("spheres file '{}' line {}: values must be finite and the radius > 0",
                                           file.string(), row));
    stored.spheres.centre.emplace_back(v[0], v[1], v[2]);
    stored.spheres.radius.push_back(v[3]);
    if (with_material) {
      if (v[4] < 0.0 || v[4] != std::floor(v[4]))
        throw std::runtime_error(fmt::format("spheres file '{}' line {}: material must be an integer >= 0",
                                             file.string(), row));
      stored.material.push_back(static_cast<std::int32_t>(v[4]));
    }
  }
  if (stored.spheres.centre.empty())
    throw std::runtime_error(fmt::format("spheres file '{}' has no spheres: expected lines x,y,z,r[,material] in m",
                                         file.string()));
  return stored;
}

BondList read_bonds_csv(const std::filesystem::path& file, std::size_t particles) {
  std::ifstream in = open_or_throw(file, "bonds");
  BondList bonds;
  std::string line;
  std::vector<double> v;
  std::size_t row = 0;
  while (std::getline(in, line)) {
    ++row;
    if (!parse_numbers(line, v)) continue;
    if (std::isnan(v[0]) && bonds.empty()) continue;  // header
    const auto n = static_cast<double>(particles);
    if (v.size() != 2 || !(v[0] >= 0 && v[0] < n && v[1] >= 0 && v[1] < n) || v[0] != std::floor(v[0]) ||
        v[1] != std::floor(v[1]) || v[0] == v[1])
      throw std::runtime_error(fmt::format("bonds file '{}' line {}: expected two different sphere indices i,j in "
                                           "[0, {}) (0-based rows of the spheres file)",
                                           file.string(), row, particles));
    const auto i = static_cast<Index>(v[0]);
    const auto j = static_cast<Index>(v[1]);
    bonds.emplace_back(std::min(i, j), std::max(i, j));
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
