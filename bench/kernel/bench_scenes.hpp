#pragma once
// The benchmark scenes, built through the plugin host exactly as a scene file would build them.
#include <cstddef>
#include <memory>

#include <map>
#include <string>

#include "shard/bond_model.hpp"
#include "shard/contact_model.hpp"
#include "shard/plugin_host.hpp"
#include "shard/simulation.hpp"

namespace shard::bench {

struct Models {
  std::unique_ptr<ContactModel> contact;
  std::unique_ptr<BondModel> bond;
};

// Plugins from the build tree; Hertz-Mindlin and the beam bond with their default (seed Table I)
// parameters, the bond's changed by `bond_params` (e.g. its effect policies switched on).
PluginHost& host();
Models default_models(const std::map<std::string, ParamValue>& bond_params = {});

// fcc block of 1 mm spheres, every nearest-neighbour pair bonded (box_fill, gap 0.7), about
// `target` spheres, 2:1:1 in x. The slabs of thickness 1.5 d at both x ends are kPrescribed and
// move apart at `pull_speed` each (m/s).
SimulationSetup bonded_block(std::size_t target, double pull_speed, const Models& models);

// Dense unbonded pack for Hertz-Mindlin: fcc sites 1 mm apart, diameters uniform in
// [0.96, 1.0] mm then scaled by 1.02 (so about half the lattice neighbours overlap by <= 2 %),
// random velocities of 0.05 m/s, gravity, a floor and four side walls; about `target` spheres.
SimulationSetup dense_pack(std::size_t target, const Models& models);

}  // namespace shard::bench
