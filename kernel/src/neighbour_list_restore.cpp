// The neighbour list's part of a checkpoint. The build positions are kept, not just the pairs:
// they decide when the list is next rebuilt, and a restart must rebuild at the same steps as
// the uninterrupted run for its history arrays to match entry for entry.
#include <fmt/format.h>

#include <stdexcept>
#include <utility>

#include "neighbour_list.hpp"
#include "shard/checkpoint.hpp"

namespace shard {

NeighbourState NeighbourList::state() const {
  NeighbourState s;
  s.skin = skin_;
  s.history_stride = stride_;
  s.first = i_;
  s.second = j_;
  s.history = history_;
  s.position_at_build = position_at_build_;
  s.wall_displacement_at_build = wall_displacement_at_build_;
  s.wall_angle_at_build = wall_angle_at_build_;
  s.wall_reach = wall_reach_;
  s.touching = touching_;
  s.rebuilds = rebuilds_;
  return s;
}

NeighbourState NeighbourList::take_state() {
  NeighbourState s;
  s.skin = skin_;
  s.history_stride = stride_;
  s.first = std::move(i_);
  s.second = std::move(j_);
  s.history = std::move(history_);
  s.position_at_build = std::move(position_at_build_);
  s.wall_displacement_at_build = wall_displacement_at_build_;
  s.wall_angle_at_build = wall_angle_at_build_;
  s.wall_reach = wall_reach_;
  s.touching = std::move(touching_);
  s.rebuilds = rebuilds_;
  i_.clear();
  j_.clear();
  history_.clear();
  position_at_build_.clear();
  touching_.clear();
  return s;
}

void NeighbourList::restore(const NeighbourState& s) { restore(NeighbourState(s)); }

void NeighbourList::restore(NeighbourState&& s) {
  if (s.history_stride != stride_)
    throw std::invalid_argument(fmt::format(
        "the checkpoint's contact history has {} values per pair, the contact model {}: restart with the "
        "contact model the run was started with",
        s.history_stride, stride_));
  if (s.first.size() != s.second.size() || s.history.size() != s.first.size() * stride_)
    throw std::invalid_argument("the checkpoint's neighbour list is inconsistent (pair and history sizes differ)");
  skin_ = s.skin;
  i_ = std::move(s.first);
  j_ = std::move(s.second);
  history_ = std::move(s.history);
  if (s.touching.size() == i_.size()) {
    touching_ = std::move(s.touching);
  } else {  // checkpoints before the flags were kept: a pair with a non-zero history has touched
    touching_.assign(i_.size(), 0);
    for (std::size_t k = 0; k < i_.size(); ++k)
      for (std::size_t q = 0; q < stride_; ++q)
        if (history_[k * stride_ + q] != 0.0) touching_[k] = 1;
  }
  position_at_build_ = std::move(s.position_at_build);
  wall_displacement_at_build_ = std::move(s.wall_displacement_at_build);
  // Checkpoints before walls could spin hold no angles: every wall was at angle zero.
  wall_angle_at_build_ = std::move(s.wall_angle_at_build);
  wall_reach_ = std::move(s.wall_reach);
  wall_angle_at_build_.resize(wall_displacement_at_build_.size(), 0.0);
  wall_reach_.resize(wall_displacement_at_build_.size(), 0.0);
  rebuilds_ = s.rebuilds;
}

}  // namespace shard
