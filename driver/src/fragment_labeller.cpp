#include "shard/driver/fragment_labeller.hpp"

#include <algorithm>
#include <functional>

namespace shard::driver {

void FragmentLabeller::before_frame(RunState& run) {
  const int every = run.scene.fragments_every;
  if (every <= 0 || run.frames_written % every != 0) return;
  if (run.whole) {
    // A decomposed run labels where its particles are (RunState::Whole::label_fragments).
    run.whole->label_fragments(labels_, sizes_);
  } else {
    const Particles& p = run.sim.particles();
    const Bonds& b = run.sim.bonds();
    const Index count = labeller_.label(p.size(), {b.i, b.j}, labels_);
    analysis::canonicalise_labels(labels_, count, p.mass, p.id);
    sizes_.assign(static_cast<std::size_t>(count), 0);
    for (Index l : labels_) ++sizes_[static_cast<std::size_t>(l)];
    std::sort(sizes_.begin(), sizes_.end(), std::greater<>());
  }
  run.frame_labels = &labels_;
  labelled_ = true;
}

void FragmentLabeller::on_finish(RunState& run) {
  if (labelled_) run.result.fragment_particles = sizes_;
}

}  // namespace shard::driver
