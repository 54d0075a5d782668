#include <fmt/format.h>

#include <stdexcept>

#include "body_placement.hpp"
#include "wall_reach.hpp"
#include "shard/scene.hpp"
#include "shard/unbreakable_zone.hpp"

namespace shard {

namespace {

// One packing per [[body]] entry (a stream's copies share it), checked as the generator made it.
GeneratedBody generate(const BodySpec& spec, const Scene& scene, const PluginHost& host,
                       const std::function<void(const std::string&)>& log) {
  const std::string section = spec.from_generator_section ? "[generator]" : "[body.generator]";
  std::unique_ptr<Generator> generator;
  try {
    generator = host.make_generator(spec.generator.name, spec.generator.params);
  } catch (const std::exception& e) {  // the plugin's own parameter checks (d_min > d_max, ...)
    throw SceneError(fmt::format("{}: {} {}", spec.generator.where, section, e.what()));
  }
  GeneratorContext ctx;
  ctx.scene_dir = scene.dir.string();
  ctx.seed = scene.seed;
  ctx.log = log;
  GeneratedBody body;
  try {
    body = generator->generate(ctx);
  } catch (const std::exception& e) {
    throw SceneError(fmt::format("{}: generator '{}' failed: {}", spec.generator.where, spec.generator.name, e.what()));
  }
  if (body.position.empty())
    throw SceneError(fmt::format("{}: generator '{}' produced no particles; check its size parameters",
                                 spec.generator.where, spec.generator.name));
  if (!body.bonds.empty() && !scene.bond)
    throw SceneError(fmt::format(
        "{}: the generator made {} bonds but the scene has no [bond] section; add one (plugin = \"beam_bond\") "
        "or switch bonding off in the generator",
        spec.generator.where, body.bonds.size()));
  return body;
}

// What a Simulation takes from the scene and its models, beside particles, bonds and dt.
void set_scene_fields(SimulationSetup& setup, const Scene& scene, const SceneInstance& inst) {
  setup.contact = inst.contact.get();
  setup.bond = inst.bond.get();
  setup.materials = scene.material_table ? scene.materials.size() : 1;
  setup.breakage = scene.breakage;
  setup.bonded_contacts = scene.bonded_contacts;
  setup.walls = scene.walls;
  setup.gravity = scene.gravity;
  setup.skin = scene.skin;
  setup.global_damping = scene.global_damping;
}

}  // namespace

SceneInstance instantiate_models(const Scene& scene, const PluginHost& host,
                                 const std::function<void(const std::string&)>& log) {
  SceneInstance out;
  // The plugins' own parameter checks (an unknown effect policy, a modulus <= 0) name the section.
  try {
    if (scene.contact) out.contact = host.make_contact(scene.contact->name, scene.contact->params);
    if (scene.contact && scene.material_table) {
      ContactMaterials table;
      table.count = scene.materials.size();
      for (const auto& m : scene.materials) {
        table.names.push_back(m.name);
        table.material.push_back(m.law);
      }
      table.pair = scene.material_pairs;
      out.contact->set_materials(table);
      for (std::size_t m = 0; m < scene.materials.size() && log; ++m)
        log(fmt::format("material {} '{}': {}", m, scene.materials[m].name,
                        scene.materials[m].density > 0 ? fmt::format("{} kg/m^3", scene.materials[m].density)
                                                       : std::string("walls only")));
    }
  } catch (const std::invalid_argument& e) {
    throw SceneError(fmt::format("{}: [contact] {}", scene.contact->where, e.what()));
  }
  try {
    if (scene.bond) out.bond = host.make_bond(scene.bond->name, scene.bond->params);
  } catch (const std::invalid_argument& e) {
    throw SceneError(fmt::format("{}: [bond] {}", scene.bond->where, e.what()));
  }
  return out;
}

SceneInstance instantiate(const Scene& scene, const PluginHost& host,
                          const std::function<void(const std::string&)>& log) {
  scene_detail::PlacedBodies placed;
  for (std::size_t s = 0; s < scene.bodies.size(); ++s) {
    const BodySpec& spec = scene.bodies[s];
    const GeneratedBody packing = generate(spec, scene, host, log);
    for (const auto& [name, value] : packing.quality)
      placed.all.quality.emplace_back(spec.from_generator_section ? name : spec.name + "." + name, value);
    scene_detail::place_body(spec, s, packing, placed);
    if (log && !spec.from_generator_section)
      log(fmt::format("body {}: {} particles, {} bonds{}", spec.name, packing.position.size(), packing.bonds.size(),
                      spec.stream ? fmt::format(", {} copies", spec.stream->copies) : std::string()));
  }
  scene_detail::check_body_overlaps(placed, scene.bodies);
  scene_detail::check_bodies_reach_walls(placed, scene.bodies, scene.walls, scene.gravity);
  // With [[material]] entries every particle is of its body's material (docs/reference/materials.md); a
  // one-material scene keeps the generator's material column as it is.
  std::vector<double> density(placed.all.position.size(), scene.density);
  for (std::size_t k = 0; k < density.size(); ++k) {
    const BodySpec& spec = scene.bodies[placed.spec_of[static_cast<std::size_t>(placed.body[k])]];
    if (!scene.material_table) continue;
    placed.all.material[k] = spec.material;
    density[k] = scene.materials[static_cast<std::size_t>(spec.material)].density;
  }
  SceneInstance out = instantiate_models(scene, host, log);
  out.body = std::move(placed.all);
  out.body_names = std::move(placed.body_names);

  SimulationSetup setup;
  const std::size_t n = out.body.position.size();
  setup.particles.reserve(n);
  for (std::size_t k = 0; k < n; ++k) {
    setup.particles.add(out.body.position[k], out.body.radius[k], density[k], out.body.material[k], placed.body[k]);
    setup.particles.velocity[k] = placed.velocity[k];
    setup.particles.omega[k] = placed.omega[k];
  }
  for (const auto& grip : scene.grips) {
    std::size_t held = 0;
    for (std::size_t k = 0; k < n; ++k) {
      const Vec3& x = setup.particles.position[k];
      if ((x.array() >= grip.min_corner.array()).all() && (x.array() <= grip.max_corner.array()).all()) {
        setup.particles.flags[k] = kPrescribed;
        setup.particles.velocity[k] = grip.velocity;
        ++held;
      }
    }
    if (held == 0)
      throw SceneError(fmt::format("{}: [[grip]] '{}' holds no particle: its box contains no particle centre",
                                   scene.file.string(), grip.name));
    if (log) log(fmt::format("grip {}: {} particles at velocity [{}, {}, {}] m/s", grip.name, held, grip.velocity.x(),
                             grip.velocity.y(), grip.velocity.z()));
  }
  const std::vector<std::size_t> zones = mark_unbreakable_zones(setup.particles, scene.walls);
  for (std::size_t w = 0; w < zones.size() && log; ++w)
    if (scene.walls[w].unbreakable_zone > 0)
      log(fmt::format("wall {}: {} particles within {} mm of its surface; the bonds between them never break",
                      scene.walls[w].name, zones[w], 1e3 * scene.walls[w].unbreakable_zone));
  setup.bonds = out.body.bonds;
  set_scene_fields(setup, scene, out);
  setup.dt = scene.dt;
  try {
    out.simulation = std::make_unique<Simulation>(std::move(setup));
  } catch (const std::invalid_argument& e) {
    throw SceneError(fmt::format("{}: {}", scene.file.string(), e.what()));
  }
  return out;
}

SimulationSetup setup_without_particles(const Scene& scene, const SceneInstance& inst, double dt) {
  SimulationSetup s;
  set_scene_fields(s, scene, inst);
  s.dt = dt;
  return s;
}

SimulationSetup setup_of(const Scene& scene, const SceneInstance& inst) {
  const Simulation& sim = *inst.simulation;
  SimulationSetup s;
  s.particles = sim.particles();
  for (std::size_t k = 0; k < sim.bonds().size(); ++k) s.bonds.emplace_back(sim.bonds().i[k], sim.bonds().j[k]);
  set_scene_fields(s, scene, inst);
  s.dt = sim.dt();
  return s;
}

}  // namespace shard
