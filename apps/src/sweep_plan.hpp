#pragma once
// What `shard sweep` runs: the parsed `--vary KEY=V1,V2,...`, and per (value, seed) the scene
// overrides of one run. KEY is a scene key as `--set` takes it; how a number reaches it depends
// on what the scene holds there:
//   - a number (or a key the scene leaves at its default): the value itself (an integer key
//     takes whole numbers only);
//   - a vector, e.g. body.shard.velocity = [0, 0, -1.5]: the value is its magnitude, the
//     direction kept (a speed, a belt velocity);
//   - KEY[i] (i = 0, 1, 2) of a vector: that component, e.g. body.shard.stream.start[2] for a
//     drop height.
// Seed index s (0 .. seeds-1) adds s to the scene's [simulation] seed (the packing) and to every
// [body.stream] seed (orientations, positions, speed scatter): s = 0 is the scene as written.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "shard/scene_override.hpp"
#include "shard/types.hpp"

namespace shard {

class PluginHost;

struct VarySpec {
  std::string key;                // as --set takes it, without [i]
  std::optional<int> component;   // KEY[i]
  std::vector<double> values;     // in the order given
  std::string text;               // the option as given, for messages
};

// Parses "KEY=V1,V2,..." (no scene needed). Throws SceneError naming the option: no '=', an
// empty key or list, an empty item, a value that is no number, a value given twice, a bad [i].
VarySpec parse_vary(const std::string& text);

enum class VaryForm { number, integer, magnitude, component };

struct SweepPlan {
  VarySpec vary;
  VaryForm form = VaryForm::number;
  Vec3 base = Vec3::Zero();       // the scene's vector (magnitude, component forms)
  std::string value_name;         // short, for progress lines: "|body.shard.velocity|", "KEY[2]", "KEY"
  std::string value_label;        // what the value is: "|body.shard.velocity| along [0, 0, -1]"
  std::uint64_t scene_seed = 1;
  std::vector<std::pair<std::string, std::uint64_t>> stream_seeds;  // [[body]] name, its stream seed
};

// Reads the scene (with `base` overrides) to decide how the values reach KEY, then loads the scene
// once per value so that a bad key or value is refused before any run, with the loader's message
// (file:line, the key, the closest valid key) after "--vary 'KEY=...':".
SweepPlan plan_sweep(const std::filesystem::path& scene, const SceneOverrides& base, const VarySpec& vary,
                     const PluginHost& host);

// The overrides of one run: `base`, the seeds of seed index `seed`, then the value.
SceneOverrides run_overrides(const SweepPlan& plan, const SceneOverrides& base, double value, std::int64_t seed);

}  // namespace shard
