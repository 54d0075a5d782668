#include "shard/scene_schema.hpp"

namespace shard {
namespace {

SceneSectionSpec simulation() {
  return {"[simulation]",
          "The run as a whole. Required.",
          {{"duration", "number", "s", "required", "simulated time span; with [stop] rules an upper bound"},
           {"dt", "auto or number", "s", "\"auto\"", "time step; \"auto\" takes the smallest step the models recommend"},
           {"seed", "integer", "", "1", "seed of the generators' random packings"},
           {"gravity", "vec3", "m/s^2", "[0, 0, 0]", "gravitational acceleration"},
           {"skin", "number", "m", "0 (automatic)", "Verlet skin of the neighbour list"},
           {"global_damping", "number", "1", "0", "Cundall's local damping, 0 to 0.99: for quasi-static loading"},
           {"settle_time", "number", "s", "0",
            "before the loading: the body rests this long under gravity on walls held in place, with "
            "settle_damping; the clock, the walls' motion and the outputs start after it"},
           {"settle_damping", "number", "1", "0.5",
            "Cundall's local damping while settling, 0 to 0.99; with dt = \"auto\" the settling steps are "
            "dt / sqrt(1 + settle_damping)"},
           {"breakage", "bool", "", "true", "the one switch for bond breakage"},
           {"bonded_contacts", "bool", "", "true",
            "false: a pair joined by an intact bond gets no contact force, its contact starts when the bond "
            "fails (as LAMMPS' BPM package); true: a bonded pair that also overlaps gets both"}},
          std::nullopt};
}

SceneSectionSpec material() {
  return {"[material]",
          "A scene of one material: its density; the contact law's parameters then all go in [contact].",
          {{"density", "number", "kg/m^3", "required", "particle density"},
           {"name", "string", "", "\"\"", "the material's name, for bodies and walls that name it"}},
          std::nullopt};
}

SceneSectionSpec materials() {
  return {"[[material]]",
          "Instead of [material], one entry per material (docs/reference/materials.md). The other keys are the "
          "contact law's per-material parameters (marked \"per [[material]]\" below).",
          {{"name", "string", "", "required", "the name bodies, walls and material pairs refer to"},
           {"density", "number", "kg/m^3", "none", "particle density; leave it out for a material only walls are "
                                                   "made of"}},
          PluginKind::Contact};
}

SceneSectionSpec material_pairs() {
  return {"[[material_pair]]",
          "With [[material]] entries: one row per pair of materials that meet. The other keys are the contact "
          "law's per-pair parameters (marked \"per [[material_pair]]\" below).",
          {{"materials", "array of strings", "", "required", "two material names, or [\"*\", \"*\"] for the default "
                                                             "row of every pair without one"}},
          PluginKind::Contact};
}

SceneSectionSpec output() {
  return {"[output]",
          "What the run writes (docs/reference/output-format.md).",
          {{"file", "string", "", "\"run.h5\"", "run file name, ending in .h5; the folder is chosen with --out"},
           {"frame_interval", "number", "s", "duration / 50", "time between frames (particles and bonds)"},
           {"series_interval", "number", "s", "duration / 2000", "time between rows of the time series"}},
          std::nullopt};
}

SceneSectionSpec analysis() {
  return {"[analysis]",
          "Analysis during the run.",
          {{"fragments_every", "integer", "", "1", "label fragments in every k-th frame; 0: never"}},
          std::nullopt};
}

SceneSectionSpec generator() {
  return {"[generator]",
          "One body, placed as generated. The other keys are the generator plugin's parameters.",
          {{"plugin", "string", "", "required", "the generator: a generator plugin below"}},
          PluginKind::Generator};
}

SceneSectionSpec bodies() {
  return {"[[body]]",
          "Instead of [generator], one entry per body (docs/reference/bodies.md).",
          {{"name", "string", "", "\"body<k>\"", "the body's name (--set body.NAME.key)"},
           {"position", "vec3", "m", "as generated", "where the body's centre of mass is placed"},
           {"rotation_axis", "vec3", "", "[0, 0, 1]", "axis of the placement rotation"},
           {"rotation_angle", "number", "degrees", "0", "placement rotation about rotation_axis, -360 to 360"},
           {"velocity", "vec3", "m/s", "[0, 0, 0]", "initial velocity"},
           {"angular_velocity", "vec3", "rad/s", "[0, 0, 0]", "initial angular velocity"},
           {"material", "string", "", "the only material", "the [[material]] the body is made of"},
           {"generator", "table", "", "required", "[body.generator]: plugin = \"...\" and its parameters"},
           {"stream", "table", "", "none", "[body.stream]: rigid copies of the body"}},
          std::nullopt};
}

SceneSectionSpec body_stream() {
  return {"[body.stream]",
          "Rigid copies of one body: along a line (start, spacing, jitter) or at random in a box (region_min, "
          "region_max).",
          {{"copies", "integer", "", "required", "number of copies"},
           {"start", "vec3", "m", "required without a region", "centre of mass of the first copy"},
           {"spacing", "vec3", "m", "required for 2+ copies", "copy k goes to start + k spacing"},
           {"jitter", "vec3", "m", "[0, 0, 0]", "half-width of a random offset per axis"},
           {"region_min", "vec3", "m", "none", "lower corner of the box of the copies' centres"},
           {"region_max", "vec3", "m", "none", "upper corner of that box"},
           {"random_orientation", "bool", "", "false", "turn each copy at random"},
           {"speed_scatter", "number", "1", "0", "relative scatter of each copy's speed, 0 to 1"},
           {"seed", "integer", "", "1", "seed of the stream's random draws"}},
          std::nullopt};
}

SceneSectionSpec contact() {
  return {"[contact]", "The contact law. The other keys are its parameters.",
          {{"plugin", "string", "", "required", "a contact plugin below"}}, PluginKind::Contact};
}

SceneSectionSpec bond() {
  return {"[bond]", "The bond law. The other keys are its parameters.",
          {{"plugin", "string", "", "required", "a bond plugin below"}}, PluginKind::Bond};
}

std::vector<SceneKeySpec> wall_shape_keys() {
  return {{"name", "string", "", "\"wall<k>\"", "the wall's name: its series in the run file, --set wall.NAME.key"},
          {"material", "string", "", "the only material", "the [[material]] the wall is made of"},
          {"shape", "string", "", "required", "\"plane\", \"cylinder\" or \"mesh\""},
          {"point", "vec3", "m", "[0, 0, 0]", "plane and cylinder: a point on the plane or the axis"},
          {"normal", "vec3", "", "[0, 0, 1]", "plane: the side particles are on"},
          {"axis", "vec3", "", "[0, 1, 0]", "cylinder: its axis"},
          {"radius", "number", "m", "required for a cylinder", "cylinder radius"},
          {"length", "number", "m", "required for a cylinder", "cylinder length, centred on point"},
          {"file", "string", "", "required for a mesh", "mesh: STL file, relative to the scene"},
          {"scale", "number", "1", "1", "mesh: factor from the STL's units to m"},
          {"offset", "vec3", "m", "[0, 0, 0]", "mesh: added to every vertex after scaling"},
          {"unbreakable_zone", "number", "m", "0 (none)",
           "bonds between particles whose centres start this close to the surface never fail: the grains under a "
           "roller or pin, which a line load on a coarse packing crushes before the specimen cracks"}};
}

std::vector<SceneKeySpec> wall_motion_keys() {
  return {{"velocity", "vec3", "m/s", "[0, 0, 0]", "translation velocity"},
          {"start_time", "number", "s", "0", "the wall is held until then"},
          {"ramp", "string", "", "\"none\"", "\"1-cos\", \"linear\" or \"none\": how the speed is reached"},
          {"ramp_time", "number", "s", "required with a ramp", "time to reach the speed"},
          {"motion_table", "string", "", "none", "CSV of time and displacement or velocity, instead of velocity"},
          {"direction", "vec3", "", "required with a table", "direction of a motion_table's travel"}};
}

std::vector<SceneKeySpec> wall_turn_and_belt_keys() {
  return {{"rotation_axis", "vec3", "", "none", "the wall turns about this direction (right-hand rule)"},
          {"rotation_point", "vec3", "m", "point", "a point on the rotation axis; required for a mesh"},
          {"angular_velocity", "number", "rad/s", "none", "turning speed, shaped by ramp"},
          {"rpm", "number", "1/min", "none", "turning speed in revolutions per minute, instead of angular_velocity"},
          {"rotation_table", "string", "", "none", "CSV of time and angle or angular_velocity"},
          {"surface_velocity", "vec3", "m/s", "none", "a belt: the surface slides over the fixed geometry"},
          {"belt_speed", "number", "m/s", "none", "a belt's speed along belt_direction, instead of surface_velocity"},
          {"belt_direction", "vec3", "", "required with belt_speed", "the belt's running direction"}};
}

SceneSectionSpec walls() {
  SceneSectionSpec s{"[[wall]]",
                     "One entry per wall: a plane, cylinder or mesh that moves, turns or carries a belt "
                     "(docs/explanation/physics.md, \"Motion\").",
                     wall_shape_keys(),
                     std::nullopt};
  for (auto&& group : {wall_motion_keys(), wall_turn_and_belt_keys()})
    s.keys.insert(s.keys.end(), group.begin(), group.end());
  return s;
}

SceneSectionSpec grips() {
  return {"[[grip]]",
          "A box whose particles are moved at a prescribed velocity (a test machine's grip).",
          {{"name", "string", "", "\"grip<k>\"", "the grip's name"},
           {"min_corner", "vec3", "m", "[0, 0, 0]", "lower corner of the box of gripped particle centres"},
           {"max_corner", "vec3", "m", "[0, 0, 0]", "upper corner; must exceed min_corner"},
           {"velocity", "vec3", "m/s", "[0, 0, 0]", "velocity of the gripped particles"}},
          std::nullopt};
}

SceneSectionSpec stop() {
  return {"[stop]",
          "Rules that end the run before its duration.",
          {{"load_walls", "array of strings", "", "[]", "walls whose summed force is the load (a test's pins)"},
           {"load_direction", "vec3", "", "[0, 0, -1]", "direction the load is measured along"},
           {"after_peak_fraction", "number", "1", "0 (off)", "stop once the load fell below this share of its peak"},
           {"max_displacement", "number", "m", "0 (off)", "stop once the load walls travelled this far"},
           {"rest_speed", "number", "m/s", "none", "with rest_time: stop once every particle is slower than this"},
           {"rest_time", "number", "s", "none", "... for this long"}},
          std::nullopt};
}

}  // namespace

const std::vector<SceneSectionSpec>& scene_schema() {
  static const std::vector<SceneSectionSpec> sections = {
      simulation(), material(), materials(), material_pairs(), generator(), bodies(), body_stream(), contact(),
      bond(),       walls(),    grips(),     stop(),           output(),    analysis()};
  return sections;
}

}  // namespace shard
