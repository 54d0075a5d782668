#pragma once
// Generator "stl_fill": fills a closed STL body with bonded spheres by the seed's advancing-front
// algorithm (sec. III): OpenVDB signed distance field, three-sphere seed, tangent placement.
#include <string>
#include <vector>

#include "shard/generator.hpp"
#include "shard/params.hpp"
#include "shard/types.hpp"

namespace shard::stl_fill {

// Surface gap below which two spheres are bonded, relative to the pair's mean radius. 0.7 gives
// a mean coordination of about 11 for the advancing-front packings (solid fraction ~0.56), like the seed's parent particle
// (235,220 bonds on 41,788 spheres: 11.3); see docs/reference/generators.md.
inline constexpr double kDefaultGap = 0.7;

struct StlFillSettings {
  std::string file;
  double scale = 1.0;
  Vec3 offset = Vec3::Zero();
  double diameter_min = 0.0;
  double diameter_max = 0.0;
  std::string psd_table;  // empty: uniform in diameter on [diameter_min, diameter_max]
  double gap = kDefaultGap;
  double voxel_size = 0.0;  // 0: diameter_min / 4
  long seed_offset = 0;
  std::string save;  // empty: do not store the packing
  double max_hole_fraction = 0.02;
  bool conform_surface = false;  // also place spheres tangent to the surface
  double weld_tolerance = 0.0;  // [m]; 0: geometry::default_weld_tolerance()
  double gap_tolerance = 0.0;   // [m]; 0: min(1e-3 x bounding-box diagonal, diameter_min / 2)
};

std::vector<ParamSpec> stl_fill_params();
StlFillSettings stl_fill_settings(const ParamSet& params);

class StlFill final : public Generator {
 public:
  explicit StlFill(StlFillSettings settings) : settings_(std::move(settings)) {}
  GeneratedBody generate(const GeneratorContext& context) const override;

 private:
  StlFillSettings settings_;
};

}  // namespace shard::stl_fill
