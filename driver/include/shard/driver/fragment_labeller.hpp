#pragma once
// Fragment labels in the frames ([output] fragments_every: every k-th frame; 0: none): each
// particle's connected set of bonded particles, numbered canonically (by mass, then particle id)
// so that ParaView's colours and the fragment analysis agree run to run. The result's
// fragment_particles are the sizes of the last labelled frame's fragments (in a decomposed run on
// rank 0).
#include <vector>

#include "shard/analysis/components.hpp"
#include "shard/driver/run_observer.hpp"

namespace shard::driver {

class FragmentLabeller : public RunObserver {
 public:
  void before_frame(RunState& run) override;
  void on_finish(RunState& run) override;

 private:
  analysis::UnionFindLabeller labeller_;
  std::vector<Index> labels_;        // the frame's rows (a decomposed run: this rank's rows)
  std::vector<std::size_t> sizes_;  // particles per fragment, largest first
  bool labelled_ = false;
};

}  // namespace shard::driver
