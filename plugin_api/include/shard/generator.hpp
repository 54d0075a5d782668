#pragma once
// Generators fill a parent body with spheres and the bonds between them (docs/reference/generators.md).
#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "shard/params.hpp"
#include "shard/types.hpp"

namespace shard {

struct GeneratorContext {
  std::string scene_dir;        // relative file names in parameters resolve against this
  std::uint64_t seed = 0;       // the scene's random seed
  std::function<void(const std::string&)> log;  // one line to the run log
};

struct GeneratedBody {
  std::vector<Vec3> position;
  std::vector<double> radius;
  std::vector<std::int32_t> material;  // empty: all material 0
  std::vector<std::pair<Index, Index>> bonds;
  // Packing quality (particle count, solid fraction, coordination, fabric deviator, ...):
  // printed and stored in the output under these names.
  std::vector<std::pair<std::string, double>> quality;
};

class Generator {
 public:
  virtual ~Generator() = default;
  virtual GeneratedBody generate(const GeneratorContext& context) const = 0;
};

}  // namespace shard
