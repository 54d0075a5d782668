#pragma once
// The analysis on top of the run-file reader (shard/run_file.hpp): a frame as the fragment
// analysis reads it, and the tables `shard fragments` stores back into the run file
// (docs/reference/fragments.md, docs/reference/output-format.md).
#include <cstddef>
#include <vector>

#include "shard/analysis/body_statistics.hpp"
#include "shard/analysis/components.hpp"
#include "shard/analysis/fragment_table.hpp"
#include "shard/analysis/size_distribution.hpp"
#include "shard/run_file.hpp"

namespace shard::analysis {

// Views into the frame's arrays: valid while the frame lives.
ParticleSample particle_sample(const FrameData& frame);
BondList bond_list(const FrameData& frame);

// The tables as they are stored (docs/reference/fragments.md): one column per field of a fragment or a body,
// the distribution's figures. The Python layer hands out the same columns.
RunTable fragment_run_table(const std::vector<Fragment>& fragments, const SizeDistribution& fsd);
RunTable body_run_table(const BodyReport& report);

// Replaces /fragments/<k:06d>: one dataset per column of the table, the distribution's
// characteristic sizes as attributes.
void write_fragment_table(RunFile& file, std::size_t k, const std::vector<Fragment>& fragments,
                          const SizeDistribution& fsd);
// Replaces /bodies/<k:06d>: one dataset per column of the per-body table, the run totals and the
// pooled distribution as attributes.
void write_body_table(RunFile& file, std::size_t k, const BodyReport& report);

}  // namespace shard::analysis
