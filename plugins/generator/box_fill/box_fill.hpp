#pragma once
// Generator "box_fill": spheres in an axis-aligned box, on a lattice (simple cubic, hcp, fcc) or
// packed by the same advancing front as stl_fill ("random": radii drawn from the PSD, seeded).
#include <string>
#include <vector>

#include "shard/generator.hpp"
#include "shard/params.hpp"
#include "shard/types.hpp"

namespace shard::box_fill {

enum class Lattice { Cubic, Hcp, Fcc, Random };

struct BoxFillSettings {
  Vec3 min_corner = Vec3::Zero();
  Vec3 max_corner = Vec3::Zero();
  Lattice lattice = Lattice::Random;
  double diameter_min = 0.0;
  double diameter_max = 0.0;
  double gap = 0.0;  // relative to the pair's mean radius, as in stl_fill
  bool bond = true;
  bool conform_surface = false;  // random lattice: also place spheres tangent to the faces
  long seed_offset = 0;
};

Lattice parse_lattice(const std::string& name);
std::vector<ParamSpec> box_fill_params();
BoxFillSettings box_fill_settings(const ParamSet& params);

class BoxFill final : public Generator {
 public:
  explicit BoxFill(BoxFillSettings settings);
  GeneratedBody generate(const GeneratorContext& context) const override;

 private:
  BoxFillSettings settings_;
};

}  // namespace shard::box_fill
