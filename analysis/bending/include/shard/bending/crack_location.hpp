#pragma once
// Where the beam cracked, from the bond-break log (run.h5 /events/bond_breaks).
//
// Definition: each break is placed at s = (midpoint - centre) . axis along the beam. The crack
// is the densest cluster of breaks: the window of width `window` along s holding the most
// breaks (ties: the first from the left); its position is the median s of the breaks inside
// that window. Between the pins means |s| <= pin_distance / 2. The window defaults to two mean
// particle diameters, the width of a crack band one bond wide on each side.
#include <cstddef>
#include <span>

#include "shard/types.hpp"

namespace shard::bending {

struct CrackLocation {
  std::size_t breaks = 0;          // all breaks considered
  std::size_t cluster_breaks = 0;  // breaks inside the densest window
  double position = 0;             // median s of the cluster, m from the beam centre
  double window = 0;               // m
  double spread = 0;               // interquartile range of s over all breaks, m
  bool found = false;              // false when there were no breaks
  bool between_pins = false;
};

CrackLocation locate_crack(std::span<const Vec3> break_midpoints, const Vec3& centre, const Vec3& axis,
                           double window, double pin_distance);

}  // namespace shard::bending
