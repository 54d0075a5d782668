#pragma once
// Generator "from_file": a stored packing, validated and reported like a generated one: either CSV
// spheres x,y,z,r[,material] and bonds i,j (as written by stl_fill's `save`) or one frame of a
// Shard run file (run.h5: positions, radii, materials and the surviving bonds of that frame).
#include <string>
#include <vector>

#include "shard/generator.hpp"
#include "shard/params.hpp"

namespace shard::from_file {

struct FromFileSettings {
  std::string spheres;         // CSV spheres file; exactly one of spheres and run is given
  std::string run;             // Shard run.h5
  long frame = -1;             // frame of `run`; negative counts from the end (-1 = last)
  std::string bonds = "auto";  // "auto": <spheres>.bonds.csv if present; "": no bonds
  std::string body;            // optional closed STL for the solid fraction
  double scale = 1.0;          // STL units -> m
  double max_overlap = 0.01;   // largest accepted overlap / min(r_i, r_j)
};

std::vector<ParamSpec> from_file_params();
FromFileSettings from_file_settings(const ParamSet& params);

class FromFile final : public Generator {
 public:
  explicit FromFile(FromFileSettings settings) : settings_(std::move(settings)) {}
  GeneratedBody generate(const GeneratorContext& context) const override;

 private:
  FromFileSettings settings_;
};

}  // namespace shard::from_file
