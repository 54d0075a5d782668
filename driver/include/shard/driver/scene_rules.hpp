#pragma once
// What every run of a scene file observes, whoever starts it (`shard run`, a measurement-loop run,
// a sweep's run): the scene's [stop] rules, and fragment labels in each frame (ParaView colours by
// them, `shard fragments` reads them).
#include <vector>

#include "shard/driver/fragment_labeller.hpp"
#include "shard/driver/stop_rules.hpp"

namespace shard::driver {

struct SceneRules {
  LoadDropStop load_drop;
  MaxDisplacementStop max_displacement;
  RestStop rest;
  FragmentLabeller labeller;

  SceneRules() = default;
  SceneRules(const SceneRules&) = delete;  // observers() hands out pointers into this object
  SceneRules& operator=(const SceneRules&) = delete;

  // In hook order: a stop rule ends the run before the labels of its row are written.
  std::vector<RunObserver*> observers() { return {&load_drop, &max_displacement, &rest, &labeller}; }
};

}  // namespace shard::driver
