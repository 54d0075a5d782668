#include "serial_backend.hpp"

#include "shard/analysis/deformation_kinetic.hpp"
#include "shard/checkpoint.hpp"

namespace shard::driver::detail {

Checkpoint SerialBackend::read_restart(const std::filesystem::path& checkpoint) const {
  return read_checkpoint(checkpoint);
}

ScenePart SerialBackend::instantiate(const Scene& scene, const PluginHost& host,
                                     const std::function<void(const std::string&)>& log) const {
  ScenePart part;
  part.instance = shard::instantiate(scene, host, log);
  part.whole = whole_scene_of(part.instance);
  return part;
}

void SerialBackend::start(const Scene&, ScenePart& part, const SimulationState* from) {
  sim_ = std::move(part.instance.simulation);
  if (from) sim_->import_state(*from);
}

void SerialBackend::step() {
  sim_->step();
  begun_.clear();
  const Particles& p = sim_->particles();
  // A state from before particle ids names a sphere by its row, which a serial run keeps.
  const bool ids = p.id.size() == p.size();
  for (const WallContactStart& c : sim_->wall_contacts_begun()) {
    const auto k = static_cast<std::size_t>(c.particle);
    begun_.push_back({ids ? p.id[k] : c.particle, p.body.size() == p.size() ? p.body[k] : 0, c.wall, c.normal});
  }
}

double SerialBackend::deformation_kinetic_energy() const {
  return analysis::deformation_kinetic_energy(sim_->particles());
}

void SerialBackend::write_frame(RunWriter& writer, RunState& state, const std::function<void()>& before_frame) {
  state.frame_labels = nullptr;
  before_frame();
  writer.write_frame(sim_->step_count(), sim_->time(), sim_->particles(), sim_->bonds(), state.frame_labels);
}

void SerialBackend::write_checkpoint(Checkpoint& loop, const std::filesystem::path& file) const {
  loop.simulation = sim_->export_state();
  shard::write_checkpoint(file, loop);
}

}  // namespace shard::driver::detail
