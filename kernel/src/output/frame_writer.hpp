#pragma once
// One snapshot group /frames/<k:06d>: particle arrays, surviving bonds as row pairs and the
// optional fragment labels.
#include <hdf5.h>

#include <cstddef>
#include <cstdint>
#include <vector>

#include "shard/bonds.hpp"
#include "shard/output.hpp"
#include "shard/particles.hpp"

namespace shard {

// Checks that the arrays agree in length and fills `pairs` (i0 j0 i1 j1 ...) with the surviving
// bonds; throws OutputError before anything is written when the snapshot is inconsistent.
void collect_frame_bonds(const Particles& particles, const Bonds& bonds,
                         const std::vector<Index>* fragment_labels, std::vector<Index>& pairs);

// Writes the datasets of one frame into `group`.
void write_frame_datasets(hid_t group, const Particles& particles, const std::vector<Index>& pairs,
                          const std::vector<Index>* fragment_labels);

// Writes this process's rows of a frame shared by several processes (FramePart): every dataset
// has the whole frame's rows; each process writes its slab.
void write_frame_part_datasets(hid_t group, const FramePart& part);

}  // namespace shard
