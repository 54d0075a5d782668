#pragma once
// A packing on disk, so a study generates a body once and every run reloads the same spheres:
//   <name>.csv        x,y,z,r,material  [m]   one sphere per line, row number = index from 0
//   <name>.bonds.csv  i,j                     one bond per line (written next to it)
// Numbers are written with 17 significant digits: a reload is bit for bit.
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "shard/geometry/advancing_front.hpp"
#include "shard/geometry/packing_quality.hpp"

namespace shard::geometry {

struct StoredPacking {
  SpherePacking spheres;
  std::vector<std::int32_t> material;  // empty when the file has no material column
  BondList bonds;
};

// The bonds file that belongs to a spheres file: "a/b.csv" -> "a/b.bonds.csv".
std::filesystem::path bonds_path_for(const std::filesystem::path& spheres_file);

// `comment` lines (the generator and its parameters) are written as '#' lines on top.
void save_packing_csv(const std::filesystem::path& spheres_file, const SpherePacking& packing, const BondList& bonds,
                      const std::vector<std::string>& comment);

// Reads spheres (x,y,z,r[,material]); throws std::runtime_error naming the file, line and fix on
// missing columns, non-numbers, r <= 0 or non-finite values.
StoredPacking read_spheres_csv(const std::filesystem::path& file);
// Reads bonds (i,j); throws on indices outside [0, particles), i == j or repeated pairs.
BondList read_bonds_csv(const std::filesystem::path& file, std::size_t particles);

}  // namespace shard::geometry

#include "shard/generator.hpp"

namespace shard::geometry {

// A parameter's file name: absolute as given, relative ones against the scene folder.
std::filesystem::path resolve_against(const std::string& scene_dir, const std::string& file);

// Hands a packing to the kernel in the generator ABI's shape.
GeneratedBody to_generated_body(SpherePacking packing, BondList bonds, std::vector<std::int32_t> material,
                                std::vector<std::pair<std::string, double>> quality);

}  // namespace shard::geometry
