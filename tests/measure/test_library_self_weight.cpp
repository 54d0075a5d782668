// The effect library's self-weight trial (scenes/measurements/effects.toml) on the default beam,
// its rollers and pins seated on the packing as the measurement commands seat them: the loading
// must begin with the beam at rest on its rollers, as a lab's beam is when the pins come.
// Switched on at the first step instead, the beam drops onto its rollers and rocks into the pins'
// arrival, and the simulated curve is that rocking, not the weight's moment.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "bending_fixture.hpp"
#include "driver_fixtures.hpp"
#include "shard/driver/run_driver.hpp"
#include "shard/measure/effect_library.hpp"
#include "shard/scene.hpp"

using namespace shard;
using namespace shard::driver;
namespace fs = std::filesystem;

namespace {

// The beam when the loading begins (after the settling, before the first loading step); then the
// run is stopped.
class StateAtLoadingStart : public RunObserver {
 public:
  void on_start(RunState& r) override {
    const Particles& p = r.sim.particles();
    for (std::size_t k = 0; k < p.size(); ++k) {
      weight += p.mass[k] * std::abs(r.scene.gravity.z());
      kinetic += 0.5 * p.mass[k] * p.velocity[k].squaredNorm() + 0.5 * p.inertia[k] * p.omega[k].squaredNorm();
      diameter += 2 * p.radius[k] / static_cast<double>(p.size());
    }
    // A wall's force is what the particles push on it: down on the rollers, up on the pins.
    for (const Wall& w : r.sim.walls()) {
      if (w.name.rfind("support", 0) == 0) support_load -= w.force.z();
      if (w.name.rfind("pin", 0) == 0) pin_load += w.force.z();
    }
    r.request_stop(StopReason::Observer, "the loading's start seen");
  }
  double weight = 0, kinetic = 0, diameter = 0, support_load = 0, pin_load = 0;
};

}  // namespace

TEST_CASE("the library's self-weight trial begins the loading with the beam at rest on its rollers") {
  const auto library = measure::read_effect_library(fs::path(SHARD_SOURCE_DIR) / "scenes/measurements/effects.toml");
  const measure::CandidateEffect* self_weight = measure::find_effect(library, "self_weight");
  REQUIRE(self_weight != nullptr);
  // Its trial size and twice it (a diagnosis fits sizes on both sides of the trial).
  for (double g : {self_weight->plausible, 2 * self_weight->plausible}) {
    CAPTURE(g);
    RunSpec spec;
    spec.scene = fs::path(SHARD_SOURCE_DIR) / "scenes/four_point_bending.toml";
    spec.out_dir = test::scratch("library_self_weight");
    spec.threads = 1;
    for (const std::string& o : self_weight->overrides(g)) spec.overrides.push_back(SceneOverride::parse(o));
    for (auto& o : BendingFixture(test::plugins()).seating_overrides(spec.scene, spec.overrides))
      spec.overrides.push_back(std::move(o));
    StateAtLoadingStart state;
    std::vector<std::string> warnings;
    run(spec, test::plugins(), {&state}, RunLog{{}, [&](const std::string& w) { warnings.push_back(w); }});
    CHECK(warnings.empty());  // the settling's own check: "still moving after settling"
    MESSAGE(state.weight, " N weight, ", state.support_load, " N on the rollers, ", state.pin_load,
            " N from the pins, ", state.kinetic, " J");
    // At rest, the rollers carry the weight and what the pins press (the rocking beam's roller
    // loads swing between 0 and 1.5 times its weight). The pins were seated on the packing before
    // it settled: where the settled beam tilts up under one, it presses a little (0.25 N at 1 g,
    // below a lab's seating preload), but the beam rests on its rollers.
    CHECK(state.support_load == doctest::Approx(state.weight + state.pin_load).epsilon(0.01));
    CHECK(state.pin_load >= 0);
    CHECK(state.pin_load < 0.1 * state.weight);
    // Its motion is below a thousandth of the work its weight does over a grain's diameter
    // (rocking, ~0.03 of it).
    CHECK(state.kinetic < 1e-3 * state.weight * state.diameter);
  }
}
