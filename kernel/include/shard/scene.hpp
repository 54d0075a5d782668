#pragma once
// A scene file (TOML) turned into validated settings: which plugins with which parameters, the
// walls, the time stepping, the output and the stop rule. Every error names file:line:column,
// the key and, for a misspelt key, the closest valid one.
#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "shard/params.hpp"
#include "shard/plugin_host.hpp"
#include "shard/scene_override.hpp"
#include "shard/simulation.hpp"
#include "shard/wall.hpp"

namespace shard {

class SceneError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct PluginChoice {
  std::string name;
  ParamSet params;
  std::string where;  // file:line:column of the section
};

// When to stop: at `duration`, or once the load on `load_walls` fell to `after_peak_fraction`
// of its peak after the first bond broke, or once the load walls moved `max_displacement`, or
// once every particle's speed stayed below `rest_speed` for `rest_time` (at rest).
struct StopRule {
  std::vector<std::string> load_walls;
  Vec3 load_direction = -Vec3::UnitZ();  // the loading walls move along this
  double after_peak_fraction = 0;        // 0: off
  double max_displacement = 0;           // m; 0: off
  double rest_speed = 0;                 // m/s; 0: off
  double rest_time = 0;                  // s; given with rest_speed

  bool is_load_wall(const std::string& wall_name) const {
    return std::find(load_walls.begin(), load_walls.end(), wall_name) != load_walls.end();
  }
};

// Particles whose centres lie in the box move at a held velocity: the clamps of a tensile test,
// a loading platen made of the body's own spheres.
struct Grip {
  std::string name;
  Vec3 min_corner = Vec3::Zero();
  Vec3 max_corner = Vec3::Zero();
  Vec3 velocity = Vec3::Zero();  // m/s; zero = clamped in place
};

// Where one body goes (docs/reference/bodies.md). The generated packing is turned by
// `rotation_angle` degrees, right-handed about `rotation_axis` through its centre of mass, then
// moved so that its centre of mass lies at `position`; it starts as a rigid body moving at
// `velocity` and spinning at `angular_velocity` about that centre. Without a position and a
// rotation the packing stays exactly where the generator put it.
struct BodyPlacement {
  std::optional<Vec3> position;          // m
  Vec3 rotation_axis = Vec3::UnitZ();
  double rotation_angle = 0;             // degrees
  Vec3 velocity = Vec3::Zero();          // m/s
  Vec3 angular_velocity = Vec3::Zero();  // rad/s, lab frame
};

// N rigid copies of one generated packing: copy k's centre of mass at start + k spacing plus a
// uniform offset in [-jitter, +jitter] per axis -- or, with a region, uniformly random in the box
// [region_min, region_max] at least one bounding diameter from the earlier copies -- turned by a
// uniformly random rotation (or the placement's), moving at the placement's velocity times a
// factor uniform in [1 - speed_scatter, 1 + speed_scatter]. The packing is generated once.
struct BodyStream {
  std::size_t copies = 1;
  Vec3 start = Vec3::Zero();    // m
  Vec3 spacing = Vec3::Zero();  // m
  Vec3 jitter = Vec3::Zero();   // m
  bool in_region = false;
  Vec3 region_min = Vec3::Zero(), region_max = Vec3::Zero();  // m, box of the centres of mass
  bool random_orientation = false;
  double speed_scatter = 0;     // relative
  std::uint64_t seed = 1;
};

// One [[body]] entry, or the single [generator] section (`from_generator_section`, placed as
// generated). Bodies are numbered in scene order, a stream's copies one after another.
struct BodySpec {
  std::string name;
  std::string where;  // file:line:column of the entry
  std::string material_name;   // as written (`material = "..."`); empty: none named
  std::string material_where;  // file:line:column of that key (of the entry when none)
  std::int32_t material = 0;   // index into Scene::materials
  PluginChoice generator;
  BodyPlacement placement;
  std::optional<BodyStream> stream;
  bool from_generator_section = false;
  std::size_t count() const { return stream ? stream->copies : 1; }
};

// Particles of different bodies closer than r_i + r_j - kBodyOverlapTolerance * min(r_i, r_j)
// at placement are refused: bodies start apart (or touching within 0.1 % of a radius).
inline constexpr double kBodyOverlapTolerance = 1e-3;

// One [[material]] entry, or the single [material] section (docs/reference/materials.md).
struct Material {
  std::string name;
  std::string where;    // file:line:column of the entry
  double density = 0;   // kg/m^3; 0: not given (a material only walls are made of)
  ParamSet law;         // the contact law's ParamScope::Material parameters ([[material]] only)
};

struct Scene {
  std::filesystem::path file;
  std::filesystem::path dir;
  std::string resolved_text;  // after --set overrides
  std::uint64_t seed = 1;
  double dt = 0;  // 0 = auto
  double duration = 0;
  double skin = 0;
  double global_damping = 0;
  double settle_time = 0;        // s before the loading (Simulation::begin_settling)
  double settle_damping = 0.5;   // Cundall's damping while settling
  Vec3 gravity = Vec3::Zero();
  bool breakage = true;
  bool bonded_contacts = true;  // false: bonded pairs get no contact force until the bond fails
  double density = 0;  // the first material's (what readers of one-material scenes take)
  // Materials (docs/reference/materials.md): one from [material], or the [[material]] entries; with
  // material_table the contact law gets per-material and per-pair parameters
  // (material_pairs[a * count + b], symmetric), bodies and walls their material index.
  std::vector<Material> materials;
  bool material_table = false;
  std::vector<ParamSet> material_pairs;
  std::string output_file = "run.h5";
  double frame_interval = 0;   // s; 0 = duration / 50
  double series_interval = 0;  // s; 0 = duration / 2000
  int fragments_every = 1;     // label fragments at every k-th frame; 0 = never
  std::vector<BodySpec> bodies;  // at least one
  std::optional<PluginChoice> contact;
  std::optional<PluginChoice> bond;
  std::vector<Wall> walls;
  std::vector<Grip> grips;
  StopRule stop;
};

// Parses and validates; plugins are looked up in `host` to check their parameters.
// `overrides` are "section.key=value" (or "wall.NAME.key=value") strings from --set.
Scene load_scene(const std::filesystem::path& file, const std::vector<std::string>& overrides,
                 const PluginHost& host);
Scene load_scene_text(const std::string& text, const std::filesystem::path& file_for_messages,
                      const std::vector<std::string>& overrides, const PluginHost& host);
// The same with typed overrides (scene_override.hpp), as code that varies a scene passes them.
Scene load_scene(const std::filesystem::path& file, const PluginHost& host, const SceneOverrides& overrides = {});
Scene load_scene_text(const std::string& text, const std::filesystem::path& file_for_messages, const PluginHost& host,
                      const SceneOverrides& overrides = {});

// The models and the generated bodies of a scene, ready to step.
struct SceneInstance {
  std::unique_ptr<ContactModel> contact;
  std::unique_ptr<BondModel> bond;
  // Every body as placed, one after another (bonds as row pairs into this list). The packing
  // quality is the single generator's, or each [[body]] entry's prefixed "<name>.".
  GeneratedBody body;
  std::vector<std::string> body_names;  // per body id: the entry's name, "name#k" for copy k of a stream
  std::unique_ptr<Simulation> simulation;
};

// Generates every body's packing with its generator plugin and builds the whole scene's Simulation.
SceneInstance instantiate(const Scene& scene, const PluginHost& host,
                          const std::function<void(const std::string&)>& log);
// The scene's contact and bond models alone (no bodies, no Simulation): what a process holding none
// of the scene's particles needs, e.g. an MPI rank other than the one that generated the scene.
SceneInstance instantiate_models(const Scene& scene, const PluginHost& host,
                                 const std::function<void(const std::string&)>& log);

// The setup the instance's Simulation was built from, taken back from it (particles with their
// ids and grips, bonds, the models, the scene's walls and settings, dt as the Simulation chose
// it): what another simulation of the same scene starts from, e.g. one decomposed over MPI ranks.
SimulationSetup setup_of(const Scene& scene, const SceneInstance& inst);
// The same without particles or bonds, for an instance of the models alone: the models, the scene's
// walls and settings, and `dt` (the whole scene's, as its Simulation chose it).
SimulationSetup setup_without_particles(const Scene& scene, const SceneInstance& inst, double dt);

// "name=value; name=value" for the output's plugin records.
std::string describe(const ParamSet& params);

}  // namespace shard
