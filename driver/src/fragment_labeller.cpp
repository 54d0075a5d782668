#include "shard/driver/fragment_labeller.hpp"

#include <algorithm>
#include <functional>

namespace shard::driver {

void FragmentLabeller::before_frame(RunState& run) {
  const int every = run.scene.fragments_every;
  if (every <= 0 || run.frames_written % every != 0) return;
  const Particles& p = run.frame_particles();
  const Bonds& b = run.frame_bonds();
  // By id: a decomposed run hands over only the ids and masses of the frame (RunState::Whole).
  count_ = labeller_.label(p.id.size(), {b.i, b.j}, labels_);
  analysis::canonicalise_labels(labels_, count_, p.mass, p.id);
  run.frame_labels = &labels_;
  labelled_ = true;
}

void FragmentLabeller::on_finish(RunState& run) {
  if (!labelled_) return;
  std::vector<std::size_t> sizes(static_cast<std::size_t>(count_), 0);
  for (Index l : labels_) ++sizes[static_cast<std::size_t>(l)];
  std::sort(sizes.begin(), sizes.end(), std::greater<>());
  run.result.fragment_particles = std::move(sizes);
}

}  // namespace shard::driver
